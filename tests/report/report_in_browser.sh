#!/bin/sh
# report_in_browser.sh TISSUEMESH PYTHON3 TESTS_DIR ARTIFACTS_DIR
# Runs the default demo (without the CalculiX check), opens its report.html in headless Chromium in
# both views and checks the screenshots (check_report_in_browser.py). The screenshots stay in
# ARTIFACTS_DIR: report-demo.png (tissues and section) and report-demo-displacement.png.
# Exit 77 (skipped) when chromium or PIL is missing.
set -eu
exe=$1; py=$2; tests=$3; artifacts=$4
command -v chromium >/dev/null 2>&1 || { echo "chromium not installed (scripts/setup.sh installs it)"; exit 77; }
"$py" -c "import PIL" 2>/dev/null || { echo "python3-pil not installed (scripts/setup.sh installs it)"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$artifacts"
"$exe" demo --skip-calculix --out "$work/demo" > "$work/demo.log" 2>&1 || { tail -30 "$work/demo.log"; exit 1; }
test -s "$work/demo/report.html" || { echo "the demo wrote no report.html"; exit 1; }
bytes=$(wc -c < "$work/demo/report.html")
echo "report.html: $bytes bytes"
[ "$bytes" -lt 20000000 ] || { echo "report.html is over 20 MB"; exit 1; }
"$py" "$tests/report/check_report_in_browser.py" "$work/demo/report.html" "$artifacts/report-demo.png"
"$py" "$tests/report/check_report_in_browser.py" "$work/demo/report.html" "$artifacts/report-demo-displacement.png" --displacement
