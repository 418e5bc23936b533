#!/usr/bin/env bash
# Runs every libFuzzer target (tests/fuzz/) for SECONDS each, JOBS at a time, from the seed
# corpora of tests/fuzz/make_seeds.py, and prints one Markdown row per target: executions,
# seconds, coverage (edges), features, corpus size, crashes. Exit 1 when any target found a crash,
# a leak, a timeout or an out-of-memory input; the inputs are kept in build-fuzz/fuzz-findings/, the logs in build-fuzz/fuzz-run/.
#   bash bench/bench_fuzz.sh [SECONDS] [JOBS]     (default 600 s, 2 at a time; CI: 60)
#   FUZZ_TARGETS="nifti vtu" bash bench/bench_fuzz.sh 600   only these targets
#   FUZZ_SEED=1 bash bench/bench_fuzz.sh 60                  libFuzzer's random seed fixed (CI), so a
#                                                             finding there can be replayed; default random
# Builds build-fuzz/ with clang (-DTISSUEMESH_FUZZ=ON), only the fuzz targets and what they link.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
SECONDS_EACH=${1:-600}
JOBS=${2:-2}
BUILD=${FUZZ_BUILD_DIR:-build-fuzz}
SEED_FLAG=()
[ -n "${FUZZ_SEED:-}" ] && SEED_FLAG=(-seed="$FUZZ_SEED")
read -r -a TARGETS <<< "${FUZZ_TARGETS:-nifti nrrd metaimage vtu config sweep}"

cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
      -DTISSUEMESH_FUZZ=ON -DTISSUEMESH_BUILD_TESTS=OFF -DTISSUEMESH_BUILD_EXAMPLES=OFF > /dev/null
cmake --build "$BUILD" -j "$JOBS" --target fuzzers > /dev/null

RUN="$BUILD/fuzz-run"
FINDINGS="$BUILD/fuzz-findings"
rm -rf "$RUN" "$FINDINGS"
mkdir -p "$RUN" "$FINDINGS"
python3 tests/fuzz/make_seeds.py . "$RUN/seeds"

# The readers' failures are InputErrors; one that needs gigabytes or seconds is a finding:
# -rss_limit_mb / -malloc_limit_mb make it one, as -timeout does for a hang. The toolkit's own
# memory budget (TISSUEMESH_MEMORY_MB, core/memory_budget.h) is set to half that limit: a header
# that asks for more is refused by the readers' budget check as it would be for a user, so an
# allocation past the limit is a reader that allocates before its check (or past it), never a
# large image whose bytes happen to exist (a detached data file may name any file on the machine).
fuzz_one() {
  local t=$1
  mkdir -p "$RUN/corpus-$t" "$RUN/tmp-$t"
  TMPDIR="$RUN/tmp-$t" TISSUEMESH_MEMORY_MB=1024 ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:fast_unwind_on_malloc=0" \
    LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0" \
    UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1" \
    "$BUILD/tests/fuzz/fuzz_$t" "${SEED_FLAG[@]}" -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -max_len=65536 -print_final_stats=1 -close_fd_mask=1 \
    -artifact_prefix="$FINDINGS/$t-" "$RUN/corpus-$t" "$RUN/seeds/$t" > "$RUN/$t.log" 2>&1 || true
}

running=0
for t in "${TARGETS[@]}"; do
  fuzz_one "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then wait -n; running=$((running - 1)); fi
done
wait

echo "| target | executions | seconds | execs/s | coverage (edges) | features | corpus | crashes |"
echo "|---|---|---|---|---|---|---|---|"
status=0
for t in "${TARGETS[@]}"; do
  log="$RUN/$t.log"
  execs=$(awk '/stat::number_of_executed_units/ {print $2}' "$log")
  secs=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log")
  rate=$(awk '/stat::average_exec_per_sec/ {print $2}' "$log")
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -n 's/.*cov: \([0-9]*\).*/\1/p' <<< "$last")
  ft=$(sed -n 's/.*ft: \([0-9]*\).*/\1/p' <<< "$last")
  corp=$(sed -n 's/.*corp: \([0-9]*\).*/\1/p' <<< "$last")
  crashes=$(find "$FINDINGS" -name "$t-*" | wc -l)
  echo "| fuzz_$t | ${execs:-?} | ${secs:-?} | ${rate:-?} | ${cov:-?} | ${ft:-?} | ${corp:-?} | $crashes |"
  if [ "$crashes" -gt 0 ] || [ -z "$execs" ]; then
    status=1
    echo "fuzz_$t: see $log" >&2
    grep -m5 -E 'ERROR|fuzz finding|SUMMARY' "$log" >&2 || true
  fi
done
exit $status
