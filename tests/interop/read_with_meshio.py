#!/usr/bin/env python3
"""Reads tissuemesh's VTU files with meshio (Debian's python3-meshio), the reader most Python FE
users have, and checks what it sees against what the file must hold.

Usage: read_with_meshio.py FILE.vtu [FILE.vtu ...]   (exit 0 when every file passes)
Each file: points finite, one block of tetra or tetra10 cells with ids in range and positive
volume (mm^3), cell data tissue_id with ids 1..N, and field data with one [tag, 3] entry per tissue
(meshio's name -> [tag, dimension] convention) whose tags are exactly 1..N in the tissue_names order.
"""
import sys

import meshio
import numpy as np


def check(path):
    mesh = meshio.read(path)
    assert np.isfinite(mesh.points).all(), "non-finite point"
    assert mesh.points.shape[1] == 3, f"points of dimension {mesh.points.shape[1]}"
    assert len(mesh.cells) == 1, f"{len(mesh.cells)} cell blocks"
    block = mesh.cells[0]
    assert block.type in ("tetra", "tetra10"), f"cell type {block.type}"
    cells = block.data
    assert cells.min() >= 0 and cells.max() < len(mesh.points), "cell node out of range"
    p = mesh.points[cells[:, :4]]
    volume = np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0]) / 6.0
    assert (volume > 0).all(), f"{int((volume <= 0).sum())} tets with volume <= 0"
    ids = np.asarray(mesh.cell_data["tissue_id"][0]).ravel()
    assert len(ids) == len(cells), "tissue_id length"
    names = np.asarray(mesh.field_data["tissue_names"]).ravel()
    n = len(names)
    assert list(names) == list(range(1, n + 1)), f"tissue_names values {names}"
    assert ids.min() >= 1 and ids.max() <= n, f"tissue ids {ids.min()}..{ids.max()} outside 1..{n}"
    tags = {k: np.asarray(v).ravel() for k, v in mesh.field_data.items()
            if np.asarray(v).size == 2 and np.asarray(v).ravel()[1] == 3}
    assert sorted(int(v[0]) for v in tags.values()) == list(range(1, n + 1)), f"tissue tags {tags}"
    print(f"{path}: {len(mesh.points)} points, {len(cells)} {block.type}, tissues "
          + ", ".join(f"{k}={int(v[0])}" for k, v in sorted(tags.items(), key=lambda kv: kv[1][0]))
          + f", total volume {volume.sum():.1f} mm^3; point data: {sorted(mesh.point_data)}")


def main():
    failed = 0
    for path in sys.argv[1:]:
        try:
            check(path)
        except (Exception, SystemExit) as e:  # every file is reported, not only the first that fails
            print(f"{path}: FAILED: {type(e).__name__}: {e}")
            failed += 1
    print(f"meshio {meshio.__version__}: {len(sys.argv) - 1 - failed} passed, {failed} failed")
    return 1 if failed or len(sys.argv) < 2 else 0


if __name__ == "__main__":
    sys.exit(main())
