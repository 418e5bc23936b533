#!/usr/bin/env python3
"""Cuts a cube out of a NIfTI-1 label image (.nii or .nii.gz, axis-aligned sform), keeping its
spacing and physical position: the voxels within HALF_MM of the LPS point (X, Y, Z), clipped to
the image. The header is copied with the new dimensions and origin.

Usage: crop_labels.py IN OUT X Y Z HALF_MM     (coordinates LPS mm, as `tissuemesh info` prints)
"""
import gzip
import struct
import sys

import numpy as np

src, dst = sys.argv[1], sys.argv[2]
centre_lps = np.array([float(v) for v in sys.argv[3:6]])
half = float(sys.argv[6])
raw = (gzip.open if src.endswith('.gz') else open)(src, 'rb').read()
hdr = bytearray(raw[:348])
vox_offset = int(struct.unpack_from('<f', hdr, 108)[0])
dim = struct.unpack_from('<8h', hdr, 40)
dtype = {2: np.uint8, 4: np.int16, 8: np.int32, 512: np.uint16, 768: np.uint32}[struct.unpack_from('<h', hdr, 70)[0]]
n = np.array(dim[1:4])
rows = [np.array(struct.unpack_from('<4f', hdr, 280 + 16 * i), dtype=float) for i in range(3)]
M = np.array([r[:3] for r in rows])
t = np.array([r[3] for r in rows])
if np.count_nonzero(M - np.diag(np.diag(M))) != 0:
    sys.exit("crop_labels.py: only axis-aligned images")
data = np.frombuffer(raw[vox_offset:vox_offset + int(np.prod(n)) * np.dtype(dtype).itemsize],
                     dtype=dtype).reshape(n[::-1])  # k, j, i
centre_ijk = np.linalg.solve(M, centre_lps * np.array([-1.0, -1.0, 1.0]) - t)  # NIfTI is RAS
h = np.abs(half / np.diag(M))
lo = np.maximum(0, np.floor(centre_ijk - h)).astype(int)
hi = np.minimum(n, np.ceil(centre_ijk + h) + 1).astype(int)
piece = np.ascontiguousarray(data[lo[2]:hi[2], lo[1]:hi[1], lo[0]:hi[0]])
origin = t + M @ lo
struct.pack_into('<8h', hdr, 40, 3, piece.shape[2], piece.shape[1], piece.shape[0], 1, 1, 1, 1)
for i in range(3):
    r = rows[i].copy()
    r[3] = origin[i]
    struct.pack_into('<4f', hdr, 280 + 16 * i, *r)
struct.pack_into('<3f', hdr, 268, *origin)  # qoffset
(gzip.open if dst.endswith('.gz') else open)(dst, 'wb').write(bytes(hdr) + raw[348:vox_offset] + piece.tobytes())
print(f"{piece.shape[2]} x {piece.shape[1]} x {piece.shape[0]} voxels from {tuple(lo)}")
