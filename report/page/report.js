// report.html's page script: renders the JSON in #report-data (written by tissuemesh) with three.js and
// Chart.js, both inlined before this script. Works offline; fetches nothing.
//
// data   = { title, command_line, notes[], scene?, charts[], tables[], meta{versions, config_yaml} }
// scene  = { nodes (base64 float32, 3 per node, mm), tissues[{id, name, color, tris (base64 uint32,
//            3 per triangle, outward)}], outer (base64 uint32 triangles of the outer boundary),
//            tets?, tet_tissue?, tet_quality? (base64 uint32 x4 / uint8 / float32 min dihedral deg),
//            tet_note?, displacement? {label, data (base64 float32, 3 per node, mm), max_mm},
//            paths[{name, points[[x,y,z]...]}], segments? (base64 float32 junction edges),
//            corridor? {entry_mm, target_mm, radius_mm}, clip_at_mm? [x,y,z] }
// The page records what it drew in #report-status (JSON) for the browser test.
(function () {
  'use strict';
  var R = JSON.parse(document.getElementById('report-data').textContent);
  var status = { errors: [], charts: 0, scene: false, first_frame_ms: null, canvas: null, chart_boxes: [] };
  window.addEventListener('error', function (e) { status.errors.push(String(e.message)); showErrors(); writeStatus(); });

  function el(tag, attrs, text) {
    var e = document.createElement(tag);
    if (attrs) Object.keys(attrs).forEach(function (k) { e.setAttribute(k, attrs[k]); });
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function showErrors() {
    var box = document.getElementById('errors');
    box.style.display = 'block';
    box.textContent = 'Page errors: ' + status.errors.join('; ');
  }
  function writeStatus() { document.getElementById('report-status').textContent = JSON.stringify(status); }
  function decode(b64, Type) {
    var bin = atob(b64), n = bin.length, bytes = new Uint8Array(n);
    for (var i = 0; i < n; ++i) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  function hexColor(s) { return new THREE.Color(s); }

  // Colour maps: viridis for |u|, a red-yellow-green ramp for element quality.
  var VIRIDIS = [[0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530], [0.207, 0.372, 0.553],
                 [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
                 [0.478, 0.821, 0.318], [0.741, 0.873, 0.150], [0.993, 0.906, 0.144]];
  var QUALITY = [[0.80, 0.10, 0.10], [0.95, 0.55, 0.10], [0.95, 0.90, 0.20], [0.45, 0.80, 0.30], [0.15, 0.60, 0.30]];
  function ramp(stops, t) {
    t = Math.min(1, Math.max(0, t)) * (stops.length - 1);
    var i = Math.min(stops.length - 2, Math.floor(t)), f = t - i, a = stops[i], b = stops[i + 1];
    return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
  }
  function colorBar(parent, stops, lo, hi, unit) {
    var box = el('div', { 'class': 'colorbar' });
    var c = el('canvas', { width: 256, height: 14 });
    var g = c.getContext('2d');
    for (var x = 0; x < 256; ++x) {
      var rgb = ramp(stops, x / 255);
      g.fillStyle = 'rgb(' + Math.round(255 * rgb[0]) + ',' + Math.round(255 * rgb[1]) + ',' + Math.round(255 * rgb[2]) + ')';
      g.fillRect(x, 0, 1, 14);
    }
    var ticks = el('div', { 'class': 'ticks' });
    for (var k = 0; k <= 4; ++k) ticks.appendChild(el('span', null, (lo + (hi - lo) * k / 4).toPrecision(3)));
    box.appendChild(c); box.appendChild(ticks); box.appendChild(el('div', { 'class': 'hint' }, unit));
    parent.appendChild(box);
    return box;
  }

  // ---- header, notes, tables ----
  document.title = R.title;
  document.getElementById('title').textContent = R.title;
  document.getElementById('cmd').textContent = R.command_line;
  var main = document.getElementById('main');
  if (R.notes && R.notes.length) {
    var notes = el('div', { 'class': 'notes' });
    R.notes.forEach(function (n) { notes.appendChild(el('div', null, n)); });
    main.appendChild(notes);
  }

  // ---- 3D view ----
  function buildScene(S) {
    main.appendChild(el('h2', null, '3D view'));
    var wrap = el('div', { 'class': 'viewer' });
    var canvas = el('canvas', { 'class': 'gl', id: 'gl' });
    var controlsBox = el('div', { 'class': 'controls' });
    wrap.appendChild(canvas); wrap.appendChild(controlsBox);
    main.appendChild(wrap);
    main.appendChild(el('div', { 'class': 'hint' }, 'Drag to rotate, wheel to zoom, right-drag to pan. Coordinates: LPS millimetres.'));

    var nodes = decode(S.nodes, Float32Array);
    var nNodes = nodes.length / 3;
    var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (var i = 0; i < nNodes; ++i)
      for (var a = 0; a < 3; ++a) { var v = nodes[3 * i + a]; if (v < lo[a]) lo[a] = v; if (v > hi[a]) hi[a] = v; }
    var center = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
    var size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);

    // Multisampling is free on a GPU but dear in a software renderer (SwiftShader, e.g. headless):
    // the first context says which one this is, and a GPU gets a fresh canvas with antialiasing.
    var params = { canvas: canvas, antialias: false, preserveDrawingBuffer: true };
    var renderer = new THREE.WebGLRenderer(params);
    var gl = renderer.getContext(), info = gl.getExtension('WEBGL_debug_renderer_info');
    var software = !info || /swiftshader|llvmpipe|software/i.test(gl.getParameter(info.UNMASKED_RENDERER_WEBGL));
    if (!software) {
      renderer.dispose();
      var fresh = canvas.cloneNode(false);
      canvas.parentNode.replaceChild(fresh, canvas);
      canvas = fresh;
      params.canvas = canvas;
      params.antialias = true;
      renderer = new THREE.WebGLRenderer(params);
    }
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xf2f4f7, 1);
    renderer.localClippingEnabled = true;
    var scene = new THREE.Scene();
    var camera = new THREE.PerspectiveCamera(35, 1, size / 100, size * 20);
    camera.up.set(0, 0, 1);  // superior up
    scene.add(new THREE.AmbientLight(0xffffff, 0.45));
    var light = new THREE.DirectionalLight(0xffffff, 0.55);
    camera.add(light); light.position.set(0.3, 0.5, 1);
    scene.add(camera);
    var controls = new THREE.OrbitControls(camera, canvas);
    controls.target.copy(center);
    var VC = (THREE.VertexColors !== undefined) ? THREE.VertexColors : true;

    var posAttr = new THREE.BufferAttribute(nodes, 3);
    var clipAt = S.clip_at_mm ? S.clip_at_mm.slice() : [center.x, center.y, center.z];
    var clip = { on: true, axis: 0, value: clipAt[0] };
    var plane = new THREE.Plane(new THREE.Vector3(-1, 0, 0), clip.value);

    // Tissue boundary surfaces, clipped by the plane.
    var tissueMeshes = [];
    var tissueGroup = new THREE.Group();
    scene.add(tissueGroup);
    S.tissues.forEach(function (t) {
      var g = new THREE.BufferGeometry();
      g.setAttribute('position', posAttr);
      g.setIndex(new THREE.BufferAttribute(decode(t.tris, Uint32Array), 1));
      g.computeVertexNormals();
      var m = new THREE.MeshLambertMaterial({ color: hexColor(t.color), side: THREE.FrontSide, clippingPlanes: [plane] });
      var mesh = new THREE.Mesh(g, m);
      tissueGroup.add(mesh);
      tissueMeshes.push({ tissue: t, mesh: mesh, visible: true });
    });

    // Cut tets: every tet the plane crosses, drawn whole (a crinkle clip) so the section shows elements.
    var tets = S.tets ? decode(S.tets, Uint32Array) : null;
    var tetTissue = S.tet_tissue ? decode(S.tet_tissue, Uint8Array) : null;
    var tetQuality = S.tet_quality ? decode(S.tet_quality, Float32Array) : null;
    var tissueColor = {};
    S.tissues.forEach(function (t) { tissueColor[t.id] = hexColor(t.color); });
    var tissueOn = {};
    S.tissues.forEach(function (t) { tissueOn[t.id] = true; });
    var nTets = tets ? tets.length / 4 : 0;
    var tetRange = null;
    if (tets) {
      tetRange = new Float32Array(6 * nTets);
      for (var t = 0; t < nTets; ++t)
        for (var ax = 0; ax < 3; ++ax) {
          var mn = Infinity, mx = -Infinity;
          for (var k = 0; k < 4; ++k) { var c = nodes[3 * tets[4 * t + k] + ax]; if (c < mn) mn = c; if (c > mx) mx = c; }
          tetRange[6 * t + 2 * ax] = mn; tetRange[6 * t + 2 * ax + 1] = mx;
        }
    }
    var colorBy = 'tissue';
    var cutMesh = null;
    var FACES = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];  // outward for a positively oriented tet
    function rebuildCut() {
      if (cutMesh) { scene.remove(cutMesh); cutMesh.geometry.dispose(); cutMesh = null; }
      if (!tets || !clip.on) return;
      var picked = [];
      for (var t = 0; t < nTets; ++t)
        if (tissueOn[tetTissue[t]] && tetRange[6 * t + 2 * clip.axis] <= clip.value && tetRange[6 * t + 2 * clip.axis + 1] >= clip.value)
          picked.push(t);
      var pos = new Float32Array(picked.length * 36), col = new Float32Array(picked.length * 36);
      var o = 0;
      picked.forEach(function (t) {
        var rgb;
        if (colorBy === 'quality') rgb = ramp(QUALITY, tetQuality[t] / 70.53);
        else { var cc = tissueColor[tetTissue[t]]; rgb = [cc.r, cc.g, cc.b]; }
        FACES.forEach(function (f) {
          for (var k = 0; k < 3; ++k) {
            var n = tets[4 * t + f[k]];
            pos[o] = nodes[3 * n]; pos[o + 1] = nodes[3 * n + 1]; pos[o + 2] = nodes[3 * n + 2];
            col[o] = rgb[0]; col[o + 1] = rgb[1]; col[o + 2] = rgb[2];
            o += 3;
          }
        });
      });
      var g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      g.setAttribute('color', new THREE.BufferAttribute(col, 3));
      g.computeVertexNormals();
      cutMesh = new THREE.Mesh(g, new THREE.MeshLambertMaterial({ vertexColors: VC, side: THREE.FrontSide }));
      cutMesh.visible = mode === 'tissues';
      scene.add(cutMesh);
      cutCount.textContent = picked.length + ' tets cut by the plane';
    }

    // Approach corridor, paths, junction curves.
    var overlays = new THREE.Group();
    scene.add(overlays);
    if (S.corridor) {
      var e = new THREE.Vector3().fromArray(S.corridor.entry_mm), tg = new THREE.Vector3().fromArray(S.corridor.target_mm);
      var len = e.distanceTo(tg);
      var cyl = new THREE.Mesh(new THREE.CylinderGeometry(S.corridor.radius_mm, S.corridor.radius_mm, len, 24, 1, true),
                               new THREE.MeshBasicMaterial({ color: 0x2060d0, transparent: true, opacity: 0.35, side: THREE.DoubleSide, depthWrite: false }));
      cyl.position.copy(e).add(tg).multiplyScalar(0.5);
      cyl.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), tg.clone().sub(e).normalize());
      overlays.add(cyl);
      var dot = new THREE.Mesh(new THREE.SphereGeometry(size / 80, 16, 12), new THREE.MeshBasicMaterial({ color: 0x2060d0 }));
      dot.position.copy(e);
      overlays.add(dot);
    }
    if (S.segments) {
      var sg = new THREE.BufferGeometry();
      sg.setAttribute('position', new THREE.BufferAttribute(decode(S.segments, Float32Array), 3));
      overlays.add(new THREE.LineSegments(sg, new THREE.LineBasicMaterial({ color: 0x101010, clippingPlanes: [plane] })));
    }

    // Displacement: the deformed outer surface coloured by |u|, the undeformed one beside it.
    var dispGroup = new THREE.Group();
    scene.add(dispGroup);
    var disp = S.displacement ? decode(S.displacement.data, Float32Array) : null;
    var outer = S.outer ? decode(S.outer, Uint32Array) : null;
    var shift = new THREE.Vector3(-(hi[0] - lo[0]) * 1.25, 0, 0);
    var deformedGeom = null, scale = 1;
    function updateDeformed() {
      var p = deformedGeom.getAttribute('position');
      for (var i = 0; i < nNodes * 3; ++i) p.array[i] = nodes[i] + scale * disp[i];
      p.needsUpdate = true;
      deformedGeom.computeVertexNormals();
    }
    if (disp && outer) {
      deformedGeom = new THREE.BufferGeometry();
      deformedGeom.setAttribute('position', new THREE.BufferAttribute(new Float32Array(nNodes * 3), 3));
      var col = new Float32Array(nNodes * 3), umax = S.displacement.max_mm > 0 ? S.displacement.max_mm : 1;
      for (var n = 0; n < nNodes; ++n) {
        var m = Math.hypot(disp[3 * n], disp[3 * n + 1], disp[3 * n + 2]);
        var rgb = ramp(VIRIDIS, m / umax);
        col[3 * n] = rgb[0]; col[3 * n + 1] = rgb[1]; col[3 * n + 2] = rgb[2];
      }
      deformedGeom.setAttribute('color', new THREE.BufferAttribute(col, 3));
      deformedGeom.setIndex(new THREE.BufferAttribute(outer, 1));
      updateDeformed();
      var deformed = new THREE.Mesh(deformedGeom, new THREE.MeshLambertMaterial({ vertexColors: VC }));
      dispGroup.add(deformed);
      var ug = new THREE.BufferGeometry();
      ug.setAttribute('position', posAttr);
      ug.setIndex(new THREE.BufferAttribute(outer, 1));
      ug.computeVertexNormals();
      var undeformed = new THREE.Mesh(ug, new THREE.MeshLambertMaterial({ color: 0xb8bec6 }));
      undeformed.position.copy(shift);
      dispGroup.add(undeformed);
    }
    (S.paths || []).forEach(function (path) {
      var pts = path.points.map(function (q) { return new THREE.Vector3().fromArray(q); });
      var pg = new THREE.BufferGeometry().setFromPoints(pts);
      var line = new THREE.Line(pg, new THREE.LineBasicMaterial({ color: 0xd01010, depthTest: false }));
      line.renderOrder = 2;
      dispGroup.add(line);
      pts.forEach(function (q, i) {
        var s = new THREE.Mesh(new THREE.SphereGeometry(size / (i === pts.length - 1 ? 70 : 110), 12, 8),
                               new THREE.MeshBasicMaterial({ color: i === pts.length - 1 ? 0xd01010 : 0x202020, depthTest: false }));
        s.position.copy(q); s.renderOrder = 3;
        dispGroup.add(s);
      });
    });

    // Controls.
    var mode = (disp && outer && window.location.hash === '#displacement') ? 'displacement' : 'tissues';
    function fieldset(title) {
      var f = el('fieldset'); f.appendChild(el('legend', null, title)); controlsBox.appendChild(f); return f;
    }
    var modeBox = null;
    if (disp && outer) {
      modeBox = fieldset('View');
      [['tissues', 'tissues and section'], ['displacement', S.displacement.label]].forEach(function (mv) {
        var lab = el('label'), r = el('input', { type: 'radio', name: 'mode', value: mv[0] });
        r.checked = mode === mv[0];
        r.addEventListener('change', function () { mode = mv[0]; applyMode(); });
        lab.appendChild(r); lab.appendChild(document.createTextNode(' ' + mv[1])); modeBox.appendChild(lab);
      });
      var sl = el('label', null, 'displacement scale ');
      var sc = el('input', { type: 'range', min: '0', max: '3', step: '0.1', value: '1' });
      sc.addEventListener('input', function () { scale = parseFloat(sc.value); updateDeformed(); render(); });
      sl.appendChild(sc); modeBox.appendChild(sl);
      colorBar(modeBox, VIRIDIS, 0, S.displacement.max_mm, '|u| (mm); left: undeformed, right: deformed' +
               ((S.paths && S.paths.length) ? '; red line: ' + S.paths.map(function (p) { return p.name; }).join(', ') : ''));
    }
    var tissueBox = fieldset('Tissues');
    tissueMeshes.forEach(function (tm) {
      var lab = el('label'), cb = el('input', { type: 'checkbox' });
      cb.checked = true;
      cb.addEventListener('change', function () {
        tm.visible = cb.checked; tissueOn[tm.tissue.id] = cb.checked; tm.mesh.visible = cb.checked; rebuildCut(); render();
      });
      var sw = el('span', { 'class': 'swatch' }); sw.style.background = tm.tissue.color;
      lab.appendChild(cb); lab.appendChild(sw); lab.appendChild(document.createTextNode(tm.tissue.name));
      tissueBox.appendChild(lab);
    });
    var clipBox = fieldset('Clipping plane');
    var clipOn = el('input', { type: 'checkbox' }); clipOn.checked = true;
    var l1 = el('label'); l1.appendChild(clipOn); l1.appendChild(document.createTextNode(' clip')); clipBox.appendChild(l1);
    var axisSel = el('select');
    ['x (L)', 'y (P)', 'z (S)'].forEach(function (n, i) { var o = el('option', { value: String(i) }, n); axisSel.appendChild(o); });
    var l2 = el('label', null, 'normal '); l2.appendChild(axisSel); clipBox.appendChild(l2);
    var slider = el('input', { type: 'range', min: '0', max: '1000', step: '1' });
    var sliderText = el('span');
    var l3 = el('label'); l3.appendChild(slider); l3.appendChild(sliderText); clipBox.appendChild(l3);
    var cutCount = el('div', { 'class': 'hint' });
    clipBox.appendChild(cutCount);
    if (tets) {
      var cb2 = el('label', null, 'section colour ');
      var colSel = el('select');
      colSel.appendChild(el('option', { value: 'tissue' }, 'tissue'));
      colSel.appendChild(el('option', { value: 'quality' }, 'min dihedral angle'));
      cb2.appendChild(colSel); clipBox.appendChild(cb2);
      var qbar = colorBar(clipBox, QUALITY, 0, 70.53, 'min dihedral angle (deg)');
      qbar.style.display = 'none';
      colSel.addEventListener('change', function () {
        colorBy = colSel.value; qbar.style.display = colorBy === 'quality' ? 'block' : 'none'; rebuildCut(); render();
      });
    }
    if (S.tet_note) clipBox.appendChild(el('div', { 'class': 'hint' }, S.tet_note));
    function sliderToValue() { return lo[clip.axis] + (hi[clip.axis] - lo[clip.axis]) * slider.value / 1000; }
    function setSliderFrom(v) { slider.value = String(Math.round(1000 * (v - lo[clip.axis]) / Math.max(1e-9, hi[clip.axis] - lo[clip.axis]))); }
    function applyClip() {
      var nrm = [0, 0, 0]; nrm[clip.axis] = -1;
      plane.normal.set(nrm[0], nrm[1], nrm[2]);
      plane.constant = clip.value;
      tissueMeshes.forEach(function (tm) { tm.mesh.material.clippingPlanes = clip.on ? [plane] : []; });
      sliderText.textContent = ' ' + clip.value.toFixed(1) + ' mm';
      rebuildCut();
    }
    clipOn.addEventListener('change', function () { clip.on = clipOn.checked; applyClip(); render(); });
    axisSel.addEventListener('change', function () {
      clip.axis = parseInt(axisSel.value, 10); clip.value = clipAt[clip.axis]; setSliderFrom(clip.value); applyClip(); render();
    });
    slider.addEventListener('input', function () { clip.value = sliderToValue(); applyClip(); render(); });
    setSliderFrom(clip.value);
    applyClip();

    function frame(target, extent, dir) {
      controls.target.copy(target);
      camera.position.copy(target).add(dir.clone().normalize().multiplyScalar(extent * 2.1));
      camera.updateProjectionMatrix();
      controls.update();
    }
    function applyMode() {
      var tissuesOn = mode === 'tissues';
      tissueGroup.visible = tissuesOn; overlays.visible = tissuesOn;
      if (cutMesh) cutMesh.visible = tissuesOn;
      dispGroup.visible = !tissuesOn;
      tissueBox.style.opacity = clipBox.style.opacity = tissuesOn ? '1' : '0.4';
      if (tissuesOn) frame(center, size, new THREE.Vector3(1.0, -0.55, 0.35));
      else frame(center.clone().add(shift.clone().multiplyScalar(0.5)), size * 1.6, new THREE.Vector3(0.25, -1.0, 0.3));
      render();
    }
    function resize() {
      var w = canvas.clientWidth, h = canvas.clientHeight;
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(1, h);
      camera.updateProjectionMatrix();
    }
    function render() { renderer.render(scene, camera); }
    controls.addEventListener('change', render);
    window.addEventListener('resize', function () { resize(); render(); });
    resize();
    applyMode();
    status.scene = true;
    var r = canvas.getBoundingClientRect();
    status.canvas = { x: r.left + window.scrollX, y: r.top + window.scrollY, w: r.width, h: r.height };
    status.mode = mode;
    status.tissue_colors = S.tissues.map(function (t) { return { name: t.name, color: t.color }; });
  }
  try {
    if (R.scene) buildScene(R.scene);
  } catch (err) {
    status.errors.push('3D view: ' + err.message); showErrors(); console.error(err);
  }

  // ---- charts ----
  if (R.charts && R.charts.length) {
    main.appendChild(el('h2', null, 'Plots'));
    var grid = el('div', { 'class': 'charts' });
    main.appendChild(grid);
    Chart.defaults.animation = false;
    Chart.defaults.font.family = '"DejaVu Sans", Helvetica, Arial, sans-serif';
    R.charts.forEach(function (spec) {
      var box = el('div', { 'class': 'chart' });
      var c = el('canvas', { id: 'chart-' + spec.id });
      box.appendChild(c); grid.appendChild(box);
      var datasets = spec.datasets.map(function (d) {
        return { label: d.label, data: d.data, backgroundColor: d.color, borderColor: d.color,
                 borderWidth: spec.kind === 'line' ? 2 : 0, pointRadius: spec.kind === 'line' ? 2 : 0,
                 stepped: false, spanGaps: true };
      });
      var scales = {
        x: { title: { display: !!spec.x_title, text: spec.x_title || '' }, stacked: !!spec.stacked },
        y: { title: { display: !!spec.y_title, text: spec.y_title || '' }, stacked: !!spec.stacked,
             type: spec.log_y ? 'logarithmic' : 'linear' }
      };
      if (spec.log_y) scales.y.ticks = { callback: function (v) {
        var e = Math.log10(v); return Math.abs(e - Math.round(e)) < 1e-9 ? '1e' + Math.round(e) : ''; } };
      if (spec.kind === 'hbar') { var t = scales.x; scales.x = scales.y; scales.y = t; scales.x.type = 'linear'; scales.y.type = 'category'; }
      new Chart(c.getContext('2d'), {
        type: spec.kind === 'line' ? 'line' : 'bar',
        data: { labels: spec.labels, datasets: datasets },
        options: { responsive: true, maintainAspectRatio: false, animation: false,
                   indexAxis: spec.kind === 'hbar' ? 'y' : 'x',
                   plugins: { title: { display: true, text: spec.title },
                              legend: { display: datasets.length > 1 || !!spec.legend } },
                   scales: scales }
      });
      var r = box.getBoundingClientRect();
      status.chart_boxes.push({ id: spec.id, x: r.left + window.scrollX, y: r.top + window.scrollY, w: r.width, h: r.height });
      status.charts += 1;
    });
  }

  // ---- tables, config, versions ----
  if ((R.tables && R.tables.length) || R.meta) main.appendChild(el('h2', null, 'Tables and run record'));
  (R.tables || []).forEach(function (t, i) {
    var d = el('details'); if (i === 0) d.open = true;
    d.appendChild(el('summary', null, t.title)); d.appendChild(el('pre', null, t.text));
    main.appendChild(d);
  });
  if (R.meta) {
    if (R.meta.versions) {
      var d = el('details'); d.appendChild(el('summary', null, 'Versions'));
      var tab = el('table', { 'class': 'kv' });
      Object.keys(R.meta.versions).sort().forEach(function (k) {
        var tr = el('tr'); tr.appendChild(el('td', null, k)); tr.appendChild(el('td', null, R.meta.versions[k])); tab.appendChild(tr);
      });
      d.appendChild(tab); main.appendChild(d);
    }
    if (R.meta.config_yaml) {
      var dc = el('details'); dc.appendChild(el('summary', null, 'Effective configuration'));
      dc.appendChild(el('pre', null, R.meta.config_yaml)); main.appendChild(dc);
    }
  }

  // Everything built and drawn once: the time from navigation start, what the load-time bench reads
  // (performance.now() runs in real time unless the browser is told to fake it).
  status.built_ms = performance.now();
  // First frame on screen.
  requestAnimationFrame(function () {
    requestAnimationFrame(function () {
      status.first_frame_ms = performance.now();
      writeStatus();
      document.body.setAttribute('data-rendered', '1');
    });
  });
  writeStatus();
})();
