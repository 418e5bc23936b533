# Shared set-up of the bench/*.sh scripts (sourced, not run): the repository root as the working
# directory, the built executable, a work directory removed on exit with the default phantom in it,
# median() (of numbers on stdin, one per line), mesh_timed() and reference_timed().
# EXE and REFERENCE, when set in the environment, replace the build's executable and machine
# reference (e.g. copies kept from one commit while the build tree moves on); give absolute paths,
# as the working directory changes to the repository root.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
EXE=${EXE:-./build/app/tissuemesh}
REFERENCE=${REFERENCE:-./build/bench/machine_reference}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
$EXE phantom --out "$WORK/phantom.nii.gz" > /dev/null

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

# mesh_timed CONFIG TIMES: `tissuemesh mesh` of the phantom into $WORK/out (replaced), appending
# the command's wall time in seconds to the file TIMES.
mesh_timed() {
  rm -rf "$WORK/out"
  local start end
  start=$(date +%s.%N)
  $EXE mesh "$WORK/phantom.nii.gz" -c "$1" -o "$WORK/out" > /dev/null
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" "BEGIN {print b - a}" >> "$2"
}

# reference_timed TIMES: appends to the file TIMES the seconds of one run of the fixed machine
# reference (bench/machine_reference.cpp: a TetGen Delaunay tetrahedralisation, independent of
# tissuemesh's code), for times given as ratios to a reference measured in the same run.
reference_timed() {
  $REFERENCE >> "$1"
}
