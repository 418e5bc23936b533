#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (tests/fuzz/CMakeLists.txt) into OUT/<target>/.

Seeds are small valid files of every layout each reader supports, made here (NIfTI-1/-2 raw and
gzip, NRRD attached/detached raw/gzip, MetaImage attached/detached raw/zlib, VTU ascii/binary),
the shipped configs and sweep files, the bad-input corpus (tests/data/bad/), whose files reach
the readers' error paths, and the inputs that once crashed a target (tests/fuzz/regressions/). The detached layouts use the fuzz targets' convention: header, a line
"@@detached@@", then the data file's bytes.

Usage: make_seeds.py REPO_ROOT OUT
"""
import base64
import glob
import os
import shutil
import struct
import sys
import zlib

ROOT, OUT = (os.path.abspath(a) for a in sys.argv[1:3])
sys.path.insert(0, os.path.join(ROOT, "tests", "data", "bad"))
import make_bad_inputs as bad  # noqa: E402  (the corpus' NIfTI/VTU writers)

SEP = b"\n@@detached@@\n"


def seed(target, name, data):
    folder = os.path.join(OUT, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def copy_all(target, patterns):
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(ROOT, pattern))):
            shutil.copyfile(path, os.path.join(OUT, target, os.path.relpath(path, ROOT).replace("/", "_")))


def main():
    labels = bad.cube_labels(n=4)
    raw = bytes(labels)
    for t in ("nifti", "nrrd", "metaimage", "vtu", "config", "sweep"):
        os.makedirs(os.path.join(OUT, t), exist_ok=True)

    # NIfTI
    nii = bad.nifti1((4, 4, 4), labels, sform=bad.IDENTITY)
    seed("nifti", "sform.nii", nii)
    seed("nifti", "sform.nii.gz", bad.gz(nii))
    seed("nifti", "qform-int16.nii", bad.nifti1((4, 4, 4), labels, "int16", pixdim=(0.5, 0.5, 2), qfac=-1, qform_code=1))
    seed("nifti", "nifti2.nii", bad.nifti2((4, 4, 4), labels))

    # NRRD
    head = ("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nspace: left-posterior-superior\n"
            "space directions: (1,0,0) (0,1,0) (0,0,2)\nspace origin: (0,0,0)\n")
    seed("nrrd", "raw.nrrd", head.encode() + b"encoding: raw\n\n" + raw)
    seed("nrrd", "gzip.nrrd", head.encode() + b"encoding: gzip\n\n" + bad.gz(raw))
    seed("nrrd", "detached-raw", head.encode() + b"encoding: raw\ndata file: data.raw" + SEP + raw)
    seed("nrrd", "detached-gzip", head.encode() + b"encoding: gzip\ndata file: data.gz" + SEP + bad.gz(raw))
    seed("nrrd", "short-ras.nrrd", head.replace("uint8", "short").replace("left-posterior", "right-anterior").encode()
         + b"endian: big\nencoding: raw\n\n" + b"".join(struct.pack(">h", v) for v in labels))
    seed("nrrd", "4d.nrrd", "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 1 4 4 4\nkinds: scalar domain domain domain\n"
         "encoding: raw\n\n".encode() + raw)

    # MetaImage
    mha = ("ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\nElementSpacing = 1 1 2\n"
           "Offset = 0 0 0\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n")
    seed("metaimage", "raw.mha", mha.encode() + b"ElementDataFile = LOCAL\n" + raw)
    z = zlib.compress(raw)
    seed("metaimage", "zlib.mha", mha.encode() + b"CompressedData = True\nCompressedDataSize = %d\n"
         b"ElementDataFile = LOCAL\n" % len(z) + z)
    seed("metaimage", "detached", mha.encode() + b"HeaderSize = 0\nElementDataFile = data.raw" + SEP + raw)
    seed("metaimage", "short-msb.mha", mha.replace("MET_UCHAR", "MET_SHORT").encode() +
         b"BinaryDataByteOrderMSB = True\nElementDataFile = LOCAL\n" + b"".join(struct.pack(">h", v) for v in labels))

    # VTU: ascii, and VTK's inline base64 binary with tissue names in the field data
    seed("vtu", "ascii.vtu", bad.vtu())
    seed("vtu", "binary.vtu", binary_vtu())

    # the bad-input corpus, each file to the reader of its kind
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "data", "bad", "*"))):
        name = os.path.basename(path)
        kind = ("nifti" if ".nii" in name else "nrrd" if name.endswith((".nrrd", ".nhdr")) else
                "metaimage" if name.endswith((".mha", ".mhd")) else "vtu" if name.endswith(".vtu") else
                "sweep" if name.startswith("sweep-") else
                "config" if name.endswith(".yaml") and name != "cases.yaml" else None)
        if kind:
            shutil.copyfile(path, os.path.join(OUT, kind, "bad_" + name))

    # inputs that once crashed a target (tests/fuzz/regressions/<target>/)
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "fuzz", "regressions", "*", "*"))):
        target = os.path.basename(os.path.dirname(path))
        shutil.copyfile(path, os.path.join(OUT, target, "regression_" + os.path.basename(path)))

    # shipped configs and sweep files
    copy_all("config", ["configs/*.yaml", "configs/materials/*.yaml", "bench/configs/*.yaml",
                        "tests/cli/inputs/*.yaml", "examples/*/*.yaml"])
    copy_all("sweep", ["configs/sweeps/*.yaml"])


def b64(fmt, values):
    data = b"".join(struct.pack("<" + fmt, v) for v in values)
    return base64.b64encode(struct.pack("<I", len(data)) + data).decode()


def binary_vtu():
    points = [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1]
    return ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
            'header_type="UInt32">\n<UnstructuredGrid>\n<FieldData><DataArray type="Int32" Name="tissue_names" '
            'NumberOfTuples="1" NumberOfComponents="2" ComponentName0="fat" ComponentName1="tumor" '
            'format="binary">%s</DataArray></FieldData>\n'
            '<Piece NumberOfPoints="5" NumberOfCells="2">\n'
            '<Points><DataArray type="Float64" NumberOfComponents="3" format="binary">%s</DataArray></Points>\n'
            '<Cells><DataArray type="Int64" Name="connectivity" format="binary">%s</DataArray>\n'
            '<DataArray type="Int64" Name="offsets" format="binary">%s</DataArray>\n'
            '<DataArray type="UInt8" Name="types" format="binary">%s</DataArray></Cells>\n'
            '<CellData Scalars="tissue_id"><DataArray type="Int32" Name="tissue_id" format="binary">%s'
            '</DataArray></CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n'
            % (b64("i", [1, 2]), b64("d", points), b64("q", [0, 1, 2, 3, 1, 2, 3, 4]), b64("q", [4, 8]),
               b64("B", [10, 10]), b64("i", [1, 2])))


if __name__ == "__main__":
    main()
