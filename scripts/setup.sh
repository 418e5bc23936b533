#!/usr/bin/env bash
# Installs the Debian 12 packages tissuemesh needs to build and test, and nothing else.
# Idempotent and non-interactive: packages already present are left alone; apt runs only when
# something is missing. Needs root (or sudo) for apt-get.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config   # toolchain
  libcgal-dev                                   # CGAL 5.5: Mesh_3 volume meshing
  libeigen3-dev                                 # Eigen 3.4: geometry and linear algebra
  libvtk9-dev                                   # VTK 9.1: NIfTI/NRRD/MetaImage readers, VTU I/O
  libtbb-dev                                    # TBB (required by CGAL's CMake config on Debian)
  libyaml-cpp-dev                               # config files
  libcli11-dev                                  # command-line parser
  nlohmann-json3-dev                            # JSON reports and run records
  zlib1g-dev                                    # gzip-compressed NIfTI / NRRD
  libgmsh-dev                                   # Gmsh 4.8 SDK: .msh export
  libtet1.5-dev                                 # TetGen 1.5: the cross-check volume mesher
  calculix-ccx                                  # CalculiX 2.20: runs the exported .inp in tests
  libsuitesparse-dev                            # CHOLMOD: the built-in solver's sparse Cholesky
  libopenblas0-pthread                          # optimised BLAS for CHOLMOD's supernodes (the
                                                #   reference BLAS is ~3x slower on the tet10 block)
  liblapack-dev libblas-dev                     # the solver's own supernodal factorisation links them
  libgtest-dev libgmock-dev                     # test suites
  python3 python3-yaml python3-meshio           # repository checks; meshio reads our VTU files back
  slurm-wlm munge                               # a real single-node Slurm for the sweep test
                                                #   (tests/slurm/local_slurm.sh starts it)
  libjs-three libjs-chart.js                    # three.js and Chart.js, inlined into report.html
  chromium fonts-dejavu-core python3-pil        # headless browser test of report.html (PIL reads
                                                #   its screenshot)
  clang libclang-rt-14-dev                      # libFuzzer targets (bench/bench_fuzz.sh; the fuzzer
                                                #   runtime is only recommended by clang)
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
