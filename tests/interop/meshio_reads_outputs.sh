#!/bin/sh
# mesh.vtu, model.vtu and solution.vtu of a coarse phantom, written by the program and read by meshio.
# Usage: meshio_reads_outputs.sh TISSUEMESH PYTHON3 SOURCE_DIR WORK_DIR
set -eu
exe=$1; py=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work"
"$exe" phantom --out labels.nii.gz --spacing 1.4 1.4 2.0 > log.txt
"$exe" mesh labels.nii.gz -c "$src/configs/phantom-coarse.yaml" -o mesh >> log.txt
"$exe" export mesh/mesh.vtu -c "$src/configs/phantom-coarse.yaml" -o model --format vtu >> log.txt
"$exe" solve mesh/mesh.vtu -c "$src/configs/phantom-coarse.yaml" -o solve >> log.txt
"$py" "$src/tests/interop/read_with_meshio.py" mesh/mesh.vtu model/model.vtu solve/solution.vtu
