#!/usr/bin/env bash
# The sanitizer run (docs/reliability.md): builds with AddressSanitizer + UndefinedBehaviorSanitizer
# into build-asan/ (RelWithDebInfo: CGAL is unusably slow unoptimised) the program and the suites
# listed below, and runs them. Any sanitizer report fails the test that triggered it
# (halt_on_error, -fno-sanitize-recover). What is left out runs in the normal build only.
#   bash scripts/sanitize.sh          build + run
#   SANITIZE_BUILD_ONLY=1 bash scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${SANITIZE_BUILD_DIR:-build-asan}
JOBS=${JOBS:-2}
# -O1 -g1 (line tables, no variables): enough for the reports' stacks; the CGAL-heavy sources
# compile faster than at -O2 -g, which matters on 2-core CI machines.
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTISSUEMESH_SANITIZE=ON \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
# The suites: the readers, configs and data model (core, image, materials, pipeline), the surface
# and volume meshing and quality tests, the program on the bad-input corpus, and the fuzz targets'
# regressions. Left to the normal run, for the CI time budget: the solver, export, workflow and
# CLI suites, CalculiX, the repository checks, meshio, Slurm.
SUITES=(test_core test_image test_materials test_pipeline test_quality test_surface test_volume)
REPLAYS=(replay_nifti replay_nrrd replay_metaimage replay_vtu replay_config replay_sweep)
LABELS='core|image|materials|pipeline|quality|surface|volume|bad_input|fuzz'
cmake --build "$BUILD_DIR" -j "$JOBS" --target tissuemesh "${SUITES[@]}" "${REPLAYS[@]}"
[ -n "${SANITIZE_BUILD_ONLY:-}" ] && exit 0

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:fast_unwind_on_malloc=0:detect_stack_use_after_return=0:strict_init_order=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
cd "$BUILD_DIR"
ctest --output-on-failure -j "$JOBS" --timeout 1800 -L "$LABELS"
