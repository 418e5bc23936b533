#!/usr/bin/env bash
# How long the demo's report.html takes to open in headless Chromium, and its size.
#
#   bash bench/bench_report_html.sh [RUNS] [BUILD_DIR]
#
# Runs `tissuemesh demo --skip-calculix` once, then opens its report.html RUNS times (default 5) in
# a fresh Chromium profile each time and reads the page's own clock: milliseconds from navigation
# start until the page has parsed its data, built the 3D scene, drawn it and drawn every plot
# (report/page/report.js, "built_ms"). Prints every run, the median, and the page size.
set -euo pipefail
runs=${1:-5}
build=${2:-build}
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/app/tissuemesh" demo --skip-calculix --out "$work/demo" > "$work/demo.log"
page="$work/demo/report.html"
times=()
for i in $(seq 1 "$runs"); do
  out=$(chromium --headless=new --no-sandbox --disable-dev-shm-usage --use-angle=swiftshader --enable-unsafe-swiftshader \
        --ignore-gpu-blocklist --no-first-run --user-data-dir="$work/profile$i" --window-size=1400,1000 \
        --dump-dom "file://$page" 2>/dev/null)
  ms=$(printf '%s' "$out" | /usr/bin/python3 -c '
import html, json, re, sys
m = re.search(r"<pre id=\"report-status\"[^>]*>(.*?)</pre>", sys.stdin.read(), re.S)
print(json.loads(html.unescape(m.group(1)))["built_ms"])')
  echo "run $i: ${ms} ms"
  times+=("$ms")
done
median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}')
tets=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["result"]["tets"])' "$work/demo/report.json")
echo
echo "| page | tets | size [MB] | open, median of $runs [ms] | runs [ms] |"
echo "|---|---|---|---|---|"
printf '| demo report.html | %s | %.1f | %.0f | %s |\n' "$tets" "$(awk -v b="$(wc -c < "$page")" 'BEGIN {print b / 1e6}')" "$median" \
  "$(printf '%.0f, ' "${times[@]}" | sed 's/, $//')"
echo
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); chromium $(chromium --version 2>/dev/null | awk '{print $2}'); load average $(cut -d' ' -f1-3 /proc/loadavg)"
