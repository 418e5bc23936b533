#!/usr/bin/env python3
"""Records, table and plot of bench/bench_convergence.sh (one JSON object per solve and line).

Usage: convergence_report.py record DIR BUDGET ELEMENT MESH_SECONDS SOLVE_SECONDS
       convergence_report.py table RECORDS.jsonl [--svg OUT.svg]

`record` prints the record of one solve from DIR/mesh/report.json and DIR/ELEMENT/solve.json.
`table` prints a Markdown table (per budget and element: tets, nodes, solve time in s, peak memory in MiB,
max |u| and the tumour's centroid displacement in mm, each as a relative difference to the finest
level of the same element and to its Richardson extrapolation) and one line per element and
quantity on the extrapolation, the solver's counts, and a table of the meshes (vertices, tets,
minimum dihedral, `mesh` wall time, each tissue's volume against its voxels). With --svg writes the tumour's centroid displacement against tets
(log axis), one line per element, the extrapolated values (else the finest level) dashed.

Richardson extrapolation (Roache, "Quantification of uncertainty in computational fluid
dynamics", Annu. Rev. Fluid Mech. 29, 1997): with the mesh size h = tets^(-1/3) and the three
finest levels h1 > h2 > h3 of values f1, f2, f3, f = f* + C h^p gives
    (f2 - f1) / (f3 - f2) = (h1^p - h2^p) / (h2^p - h3^p),
solved for the observed order p by bisection, and f* = f3 + (f3 - f2) / ((h2 / h3)^p - 1).
It is reported as not applicable when the differences change sign (no monotone sequence), when
no p in [0.05, 20] solves the equation, or when p is outside [P_MIN, P_MAX] (the sequence is not
in its asymptotic range: an extrapolation would be a guess).
Only the standard library.
"""
import argparse
import json
import math

P_MIN, P_MAX = 0.5, 4.0
ELEMENTS = {"tet10": "tet10", "tet4-nodal": "tet4, nodal pressure"}
COLOURS = {"tet10": "#1f77b4", "tet4-nodal": "#d62728"}


def richardson(levels):
    """levels: [(tets, value)] sorted by tets ascending. Returns a dict with p, f* or why not."""
    if len(levels) < 3:
        return {"applicable": False, "why": f"{len(levels)} level(s): three are needed"}
    (n1, f1), (n2, f2), (n3, f3) = levels[-3:]
    h1, h2, h3 = (n ** (-1.0 / 3.0) for n in (n1, n2, n3))
    e21, e32 = f2 - f1, f3 - f2
    base = {"tets": [n1, n2, n3]}
    if e32 == 0.0 or e21 * e32 <= 0.0:
        return {**base, "applicable": False, "why": "the differences between levels change sign (oscillating)"}
    target = e21 / e32

    def g(p):
        return (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p) - target

    lo, hi = 0.05, 20.0
    if g(lo) * g(hi) > 0.0:
        return {**base, "applicable": False, "why": "no observed order in [0.05, 20] fits the three levels"}
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0.0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    if not P_MIN <= p <= P_MAX:
        return {**base, "applicable": False, "p": p,
                "why": f"observed order p = {p:.2f} is outside [{P_MIN}, {P_MAX}]"}
    f_star = f3 + e32 / ((h2 / h3) ** p - 1.0)
    return {**base, "applicable": True, "p": p, "f_star": f_star}


def rel(a, b):
    return "–" if b is None or b == 0.0 else f"{100.0 * (a - b) / abs(b):+.2f} %"


def svg_plot(by_element, extrap, path):
    """Tumour centroid displacement [mm] against tets on a log axis."""
    W, H, L, R, T, B = 760, 440, 80, 240, 40, 60
    pts = [(r["tets"], r["tumor_u_magnitude_mm"]) for rs in by_element.values() for r in rs]
    refs = [(el, e) for el, e in extrap.items()]
    ys = [y for _, y in pts] + [e["value"] for _, e in refs]
    x0, x1 = math.log10(min(x for x, _ in pts)) - 0.08, math.log10(max(x for x, _ in pts)) + 0.08
    ylo, yhi = min(ys), max(ys)
    pad = 0.08 * (yhi - ylo or 1.0)
    ylo, yhi = ylo - pad, yhi + pad
    step = 10 ** math.floor(math.log10((yhi - ylo) / 4))
    for m in (1, 2, 5, 10):
        if (yhi - ylo) / (m * step) <= 8:
            step *= m
            break

    def X(n):
        return L + (math.log10(n) - x0) / (x1 - x0) * (W - L - R)

    def Y(v):
        return T + (yhi - v) / (yhi - ylo) * (H - T - B)

    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" viewBox="0 0 {W} {H}" '
         'font-family="sans-serif" font-size="12">',
         f'<rect width="{W}" height="{H}" fill="white"/>',
         f'<text x="{L + (W - L - R) / 2}" y="22" text-anchor="middle" font-size="14">'
         'Tumour centroid displacement under prone gravity, default phantom</text>']
    # grid and axes
    v = math.ceil(ylo / step) * step
    while v <= yhi:
        o.append(f'<line x1="{L}" x2="{W - R}" y1="{Y(v):.1f}" y2="{Y(v):.1f}" stroke="#ddd"/>')
        o.append(f'<text x="{L - 6}" y="{Y(v) + 4:.1f}" text-anchor="end">{v:.{max(0, -math.floor(math.log10(step)))}f}</text>')
        v += step
    for e in range(math.floor(x0), math.ceil(x1) + 1):
        for m in range(1, 10):
            n = m * 10 ** e
            if not x0 <= math.log10(n) <= x1:
                continue
            o.append(f'<line x1="{X(n):.1f}" x2="{X(n):.1f}" y1="{T}" y2="{H - B}" stroke="{"#ccc" if m == 1 else "#eee"}"/>')
            if m in (1, 2, 5):
                label = f"{n // 1000:,}K" if n >= 1000 else f"{n}"
                o.append(f'<text x="{X(n):.1f}" y="{H - B + 16}" text-anchor="middle">{label}</text>')
    o.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="black"/>')
    o.append(f'<text x="{L + (W - L - R) / 2}" y="{H - 18}" text-anchor="middle">tets (log scale)</text>')
    o.append(f'<text transform="translate(20 {T + (H - T - B) / 2}) rotate(-90)" text-anchor="middle">'
             'tumour centroid displacement [mm]</text>')
    # reference lines, then the data
    ly = T + 10
    for el, rs in by_element.items():
        c = COLOURS.get(el, "black")
        e = extrap[el]
        o.append(f'<line x1="{L}" x2="{W - R}" y1="{Y(e["value"]):.1f}" y2="{Y(e["value"]):.1f}" stroke="{c}" '
                 'stroke-dasharray="6 4" stroke-width="1.2"/>')
        line = " ".join(f"{X(r['tets']):.1f},{Y(r['tumor_u_magnitude_mm']):.1f}" for r in rs)
        o.append(f'<polyline points="{line}" fill="none" stroke="{c}" stroke-width="2"/>')
        for r in rs:
            o.append(f'<circle cx="{X(r["tets"]):.1f}" cy="{Y(r["tumor_u_magnitude_mm"]):.1f}" r="4" fill="{c}"/>')
        o.append(f'<line x1="{W - R + 12}" x2="{W - R + 40}" y1="{ly}" y2="{ly}" stroke="{c}" stroke-width="2"/>')
        o.append(f'<circle cx="{W - R + 26}" cy="{ly}" r="4" fill="{c}"/>')
        o.append(f'<text x="{W - R + 46}" y="{ly + 4}">{ELEMENTS.get(el, el)}</text>')
        o.append(f'<line x1="{W - R + 12}" x2="{W - R + 40}" y1="{ly + 18}" y2="{ly + 18}" stroke="{c}" '
                 'stroke-dasharray="6 4"/>')
        o.append(f'<text x="{W - R + 46}" y="{ly + 22}">{e["label"]}</text>')
        ly += 48
    o.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(o) + "\n")


def record(d, budget, element, mesh_s, wall_s):
    m = json.load(open(f"{d}/mesh/report.json"))["result"]["volume_mesh"]
    s = json.load(open(f"{d}/{element}/solve.json"))
    v, r = s["solver"], s["results"]
    tumor = next(t for t in r["tissues"] if t["name"] == "tumor")
    return {"budget": budget, "element": element, "vertices": json.load(open(f"{d}/mesh/report.json"))["result"]["vertices"],
            "tets": s["model"]["elements"], "nodes": s["model"]["nodes"], "free_dofs": v["free_dofs"],
            "min_dihedral_deg": m["quality"]["total"]["min_dihedral_deg"],
            "tets_below_10deg": m["quality"]["total"]["tets_below_10deg"],
            "volume_error_rel": {t["name"]: t["volume_error_rel"] for t in m["quality"]["tissues"]},
            "mesh_wall_s": mesh_s, "solve_wall_s": wall_s, "solver_s": v["seconds"], "peak_mib": s["peak_memory_mib"],
            "increments": v["increments_attempted"], "iterations": v["total_iterations"],
            "factorisations": v["factorisations"], "failed_factorisations": v["failed_factorisations"],
            "max_u_mm": r["max_displacement_mm"], "tumor_u_mm": tumor["centroid_displacement_mm"],
            "tumor_u_magnitude_mm": tumor["centroid_displacement_magnitude_mm"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True)
    rec = sub.add_parser("record")
    rec.add_argument("dir")
    rec.add_argument("budget", type=int)
    rec.add_argument("element")
    rec.add_argument("mesh_seconds", type=float)
    rec.add_argument("solve_seconds", type=float)
    tab = sub.add_parser("table")
    tab.add_argument("records")
    tab.add_argument("--svg")
    a = ap.parse_args()
    if a.command == "record":
        print(json.dumps(record(a.dir, a.budget, a.element, a.mesh_seconds, a.solve_seconds)))
        return
    records = [json.loads(line) for line in open(a.records) if line.strip()]
    by_element = {}
    for r in records:
        by_element.setdefault(r["element"], []).append(r)
    for rs in by_element.values():
        rs.sort(key=lambda r: r["tets"])

    quantities = {"max_u_mm": "max |u|", "tumor_u_magnitude_mm": "tumour centroid displacement"}
    ex = {(el, q): richardson([(r["tets"], r[q]) for r in rs]) for el, rs in by_element.items() for q in quantities}

    print("| budget [vertices] | element | tets | nodes | solve [s] | peak memory [MiB] | max \\|u\\| [mm] "
          "| vs finest | vs extrapolated | tumour centroid displacement [mm] | vs finest | vs extrapolated |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in sorted(records, key=lambda r: (r["budget"], list(ELEMENTS).index(r["element"])
                                            if r["element"] in ELEMENTS else 9)):
        el = r["element"]
        finest = by_element[el][-1]
        cells = []
        for q in quantities:
            e = ex[(el, q)]
            cells += [f"{r[q]:.3f}", rel(r[q], finest[q]), rel(r[q], e["f_star"] if e["applicable"] else None)]
        print(f"| {r['budget']:,} | {ELEMENTS.get(el, el)} | {r['tets']:,} | {r['nodes']:,} | {r['solver_s']:.1f} "
              f"| {r['peak_mib']:.0f} | " + " | ".join(cells) + " |")
    print()
    for (el, q), e in ex.items():
        name = f"- {ELEMENTS.get(el, el)}, {quantities[q]}: "
        finest = by_element[el][-1]
        if e["applicable"]:
            print(name + f"observed order p = {e['p']:.2f} from the levels of {', '.join(f'{n:,}' for n in e['tets'])} "
                  f"tets; extrapolated {e['f_star']:.3f} mm (finest level {finest[q]:.3f} mm, {rel(finest[q], e['f_star'])})")
        else:
            print(name + "Richardson extrapolation not applicable: " + e["why"])
    print("- finest levels: " + "; ".join(f"{ELEMENTS.get(el, el)} {rs[-1]['budget']:,} vertices, {rs[-1]['tets']:,} tets"
                                           for el, rs in by_element.items()))
    print("- per solve (budget element: load increments, Newton iterations, factorisations (+ failed attempts), "
          "command wall time s): " +
          "; ".join(f"{r['budget']} {r['element']}: {r['increments']}, {r['iterations']}, {r['factorisations']} "
                    f"(+{r['failed_factorisations']}), {r['solve_wall_s']:.1f}"
                    for r in sorted(records, key=lambda r: (r["budget"], r["element"]))))
    print()
    meshes = {r["budget"]: r for r in records}
    names = list(next(iter(meshes.values()))["volume_error_rel"])
    print("| budget [vertices] | vertices | tets | min dihedral [deg] | tets < 10 deg | `mesh` wall [s] | volume error: "
          + " / ".join(names) + " [%] |")
    print("|---|---|---|---|---|---|---|")
    for b, r in sorted(meshes.items()):
        print(f"| {b:,} | {r['vertices']:,} | {r['tets']:,} | {r['min_dihedral_deg']:.2f} | {r['tets_below_10deg']} "
              f"| {r['mesh_wall_s']:.1f} | " + " / ".join(f"{100 * r['volume_error_rel'][n]:+.2f}" for n in names) + " |")
    if a.svg:
        refs = {}
        for el, rs in by_element.items():
            e = ex[(el, "tumor_u_magnitude_mm")]
            refs[el] = ({"value": e["f_star"], "label": f"extrapolated (p = {e['p']:.2f})"} if e["applicable"] else
                        {"value": rs[-1]["tumor_u_magnitude_mm"], "label": f"finest level, {rs[-1]['tets']:,} tets"})
        svg_plot(by_element, refs, a.svg)
        print(f"\nplot: {a.svg}")


if __name__ == "__main__":
    main()
