#!/usr/bin/env python3
"""Writes the bad-input corpus files of this folder (tests/data/bad/cases.yaml uses them).

The files are checked in; this script documents how each was made and rewrites them identically
(gzip with mtime 0). Cases that need the file system in a particular state at run time (long and
non-ASCII paths, directories, read-only or full output folders, signals) are made by
tests/bad_input/run_bad_case.py instead.

Usage: python3 make_bad_inputs.py [FOLDER]   (default: the folder of this script)
"""
import gzip
import math
import os
import struct
import sys

OUT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(__file__))


def write(name, data):
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)


def gz(data):
    return gzip.compress(data, mtime=0)


# ------------------------------------------------------------------------------------ label data

def cube_labels(n=8, inner=1, fill=0):
    """n^3 voxels, x fastest: `inner` in [2, n-2)^3, `fill` elsewhere."""
    v = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                v.append(inner if all(2 <= c < n - 2 for c in (i, j, k)) else fill)
    return v


def pack(values, fmt):
    return b"".join(struct.pack("<" + fmt, x) for x in values)


# ------------------------------------------------------------------------------------ NIfTI-1

DT = {"uint8": (2, 8, "B"), "int16": (4, 16, "h"), "int8": (256, 8, "b"), "uint16": (512, 16, "H"),
      "float32": (16, 32, "f"), "float64": (64, 64, "d")}


def nifti1(dims, values, dtype="uint8", pixdim=(1, 1, 1), qfac=1.0, sform=None, qform_code=0,
           raw_dims=None):
    """A single-file NIfTI-1 image. `sform`: 3 rows of 4 numbers (sform_code 1) or None."""
    code, bitpix, fmt = DT[dtype]
    h = bytearray(352)
    struct.pack_into("<i", h, 0, 348)
    d = raw_dims or (3, dims[0], dims[1], dims[2], 1, 1, 1, 1)
    struct.pack_into("<8h", h, 40, *d)
    struct.pack_into("<hh", h, 70, code, bitpix)
    struct.pack_into("<8f", h, 76, qfac, *pixdim, 1, 1, 1, 1)
    struct.pack_into("<f", h, 108, 352.0)
    struct.pack_into("<f", h, 112, 1.0)
    h[123] = 2  # mm
    struct.pack_into("<hh", h, 252, qform_code, 1 if sform else 0)
    if sform:
        for r, row in enumerate(sform):
            struct.pack_into("<4f", h, 280 + 16 * r, *row)
    h[344:348] = b"n+1\0"
    return bytes(h) + pack(values, fmt)


def nifti2(dims, values):
    """A NIfTI-2 header (64-bit sizes) followed by `values` as uint8."""
    h = bytearray(544)
    struct.pack_into("<i", h, 0, 540)
    h[4:12] = b"n+2\0\r\n\x1a\n"
    struct.pack_into("<hh", h, 12, 2, 8)
    struct.pack_into("<8q", h, 16, 3, dims[0], dims[1], dims[2], 1, 1, 1, 1)
    struct.pack_into("<8d", h, 104, 1, 1, 1, 1, 1, 1, 1, 1)
    struct.pack_into("<q", h, 168, 544)
    struct.pack_into("<d", h, 176, 1.0)
    struct.pack_into("<i", h, 500, 2)
    return bytes(h) + bytes(values)


IDENTITY = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]


def main():
    os.makedirs(OUT, exist_ok=True)
    ok = nifti1((8, 8, 8), cube_labels(), sform=IDENTITY)
    write("ok.nii.gz", gz(ok))

    # gzip: cut in half, a corrupted checksum, corrupted deflate data, an empty file
    good = gz(ok)
    write("truncated.nii.gz", good[: len(good) // 2])
    crc = bytearray(good)
    crc[-8] ^= 0xFF
    write("bad-crc.nii.gz", bytes(crc))
    mid = bytearray(good)
    for i in range(20, 40):
        mid[i] ^= 0x5A
    write("corrupt-deflate.nii.gz", bytes(mid))
    write("empty.nii.gz", b"")

    # sizes: data cut short, dims far beyond the file, NIfTI-2 sizes beyond an int
    write("truncated.nii", ok[: 352 + 100])
    write("dims-exceed-file.nii", nifti1((8, 8, 8), cube_labels(), raw_dims=(3, 100, 100, 100, 1, 1, 1, 1)))
    write("nifti2-huge-dims.nii", nifti2((1 << 40, 1 << 40, 1 << 40), cube_labels()))

    # geometry
    write("zero-pixdim.nii", nifti1((8, 8, 8), cube_labels(), pixdim=(0, 1, 1)))
    write("negative-pixdim.nii", nifti1((8, 8, 8), cube_labels(), pixdim=(-1, 1, 1), qform_code=1))
    nan_rows = [[math.nan, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]
    write("nan-sform.nii", nifti1((8, 8, 8), cube_labels(), sform=nan_rows))
    skew = [[1, 0, 0, 0], [1, 1, 0, 0], [0, 0, 1, 0]]
    write("non-orthogonal-sform.nii", nifti1((8, 8, 8), cube_labels(), sform=skew))

    # label types and values
    write("float-labels.nii", nifti1((8, 8, 8), [float(x) for x in cube_labels()], "float32", sform=IDENTITY))
    write("int16-negative.nii.gz", gz(nifti1((8, 8, 8), cube_labels(inner=1, fill=-5), "int16", sform=IDENTITY)))
    write("one-voxel.nii.gz", gz(nifti1((1, 1, 1), [1], sform=IDENTITY)))
    write("single-tissue.nii.gz", gz(nifti1((8, 8, 8), cube_labels(inner=1, fill=1), sform=IDENTITY)))
    write("all-background.nii.gz", gz(nifti1((8, 8, 8), cube_labels(inner=0, fill=0), sform=IDENTITY)))
    many = [0] * (22 ** 3)
    for n in range(10000):
        many[n] = n + 1
    write("labels-10k.nii.gz", gz(nifti1((22, 22, 22), many, "int16", sform=IDENTITY)))
    wide = nifti1((8, 8, 8), cube_labels(), pixdim=(1000, 1000, 1000),
                  sform=[[1000, 0, 0, 0], [0, 1000, 0, 0], [0, 0, 1000, 0]])
    write("km-spacing.nii.gz", gz(wide))

    # NRRD
    raw8 = bytes(cube_labels())
    nrrd = ("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n"
            "space: left-posterior-superior\n")
    write("dims-overflow.nrrd", "NRRD0004\ntype: uint64\ndimension: 3\n"
          "sizes: 2000000000 2000000000 2000000000\nendian: little\nencoding: raw\n\n")
    write("huge-dims.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 40000 40000 40000\nencoding: raw\n\n")
    write("dims-exceed-file.nrrd", nrrd.replace("sizes: 8 8 8", "sizes: 100 100 100") + "\n" + "x" * 10)
    write("missing-data.nhdr", nrrd + "data file: missing-voxels.raw\n")
    write("corrupt-gzip.nrrd", nrrd.replace("encoding: raw", "encoding: gzip").encode() + b"\n" +
          b"\x1f\x8b\x08\x00" + bytes(range(200)))
    write("zero-spacing.nrrd", nrrd + "space directions: (0,0,0) (0,1,0) (0,0,1)\n\n" + raw8.decode("latin1"))
    write("nan-direction.nrrd", nrrd + "space directions: (nan,0,0) (0,1,0) (0,0,1)\n\n" + raw8.decode("latin1"))
    write("non-orthogonal.nrrd", nrrd + "space directions: (1,0,0) (1,1,0) (0,0,1)\n\n" + raw8.decode("latin1"))
    write("double-labels.nrrd", (nrrd.replace("uint8", "double") + "endian: little\n\n").encode() +
          pack([float(x) for x in cube_labels()], "d"))
    write("int8-negative.nrrd", nrrd.replace("uint8", "int8").encode() + b"\n" + pack(cube_labels(inner=1, fill=-3), "b"))

    # MetaImage
    mha = ("ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_UCHAR\n"
           "ElementSpacing = 1 1 1\n")
    write("dims-overflow.mha", mha.replace("8 8 8", "2147483647 2147483647 2147483647") + "ElementDataFile = LOCAL\n")
    write("negative-spacing.mha", mha.replace("ElementSpacing = 1 1 1", "ElementSpacing = -1 1 1").encode() +
          b"ElementDataFile = LOCAL\n" + raw8)
    write("nan-transform.mha", mha.encode() + b"TransformMatrix = nan 0 0 0 1 0 0 0 1\nElementDataFile = LOCAL\n" + raw8)
    write("non-orthogonal.mha", mha.encode() + b"TransformMatrix = 1 0 0 1 1 0 0 0 1\nElementDataFile = LOCAL\n" + raw8)
    write("uint16-labels.mha", mha.replace("MET_UCHAR", "MET_USHORT").encode() + b"ElementDataFile = LOCAL\n" +
          pack(cube_labels(inner=40000, fill=0), "H"))
    write("missing-data.mhd", mha + "ElementDataFile = missing-voxels.raw\n")
    write("long-name.mha", mha.encode() + b"Name = " + b"breast " * 43 + b"\nElementDataFile = LOCAL\n" + raw8)
    write("data-file-name-too-long.mhd", mha + "ElementDataFile = " + "v" * 300 + ".raw\n")

    # VTU meshes (ASCII, as a user might edit or cut one)
    write("ok.vtu", vtu())
    write("not-xml.vtu", "this is not a mesh\n")
    write("truncated.vtu", vtu()[:300])
    write("no-tissue-id.vtu", vtu(cell_data=""))
    write("hexahedron.vtu", vtu(types="12", connectivity="0 1 2 3 4 5 6 7", offsets="8", points=8, ids="1"))
    write("huge-cell-offset.vtu", vtu(offsets="4 8589934600"))
    write("decreasing-cell-offsets.vtu", vtu(offsets="8 4"))
    write("nan-point.vtu", vtu(coords="nan 0 0  1 0 0  0 1 0  0 0 1  1 1 1"))
    write("bad-node-index.vtu", vtu(connectivity="0 1 2 3  1 2 3 99"))
    write("huge-tissue-id.vtu", vtu(ids="1 2000000000"))
    write("short-tissue-id.vtu", vtu(ids="1", id_count=1))


def vtu(coords="0 0 0  1 0 0  0 1 0  0 0 1  1 1 1", connectivity="0 1 2 3  1 2 3 4",
        offsets="4 8", types="10 10", points=5, ids="1 1", id_count=None, cell_data=None):
    cells = len(types.split())
    if points != 5:
        coords = " ".join("%d %d %d" % (i & 1, (i >> 1) & 1, (i >> 2) & 1) for i in range(points))
    if cell_data is None:
        cell_data = ('<CellData Scalars="tissue_id"><DataArray type="Int32" Name="tissue_id" '
                     'format="ascii">%s</DataArray></CellData>' % ids)
    return ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">\n'
            '<UnstructuredGrid><Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
            '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">%s</DataArray></Points>\n'
            '<Cells><DataArray type="Int64" Name="connectivity" format="ascii">%s</DataArray>\n'
            '<DataArray type="Int64" Name="offsets" format="ascii">%s</DataArray>\n'
            '<DataArray type="UInt8" Name="types" format="ascii">%s</DataArray></Cells>\n'
            '%s\n</Piece></UnstructuredGrid></VTKFile>\n'
            % (points, cells, coords, connectivity, offsets, types, cell_data))


if __name__ == "__main__":
    main()
