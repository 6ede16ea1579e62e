#!/bin/sh
# Screenshots a grader report (REPORT_DIR/index.html) with headless Chromium,
# to look at the page without a desktop:
#   tools/screenshot_report.sh REPORT_DIR OUT.png [WIDTH,HEIGHT]
# Exits 77 (the "skipped" code of CTest) when Chromium is not installed
# (Debian 12: apt-get install chromium).
set -eu

if [ $# -lt 2 ]; then
    echo "usage: $0 REPORT_DIR OUT.png [WIDTH,HEIGHT]" >&2
    exit 2
fi
report_dir=$1
out=$2
size=${3:-1400,2000}

browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$browser" ]; then
    echo "screenshot_report.sh: chromium is not installed (Debian: apt-get install chromium); skipped" >&2
    exit 77
fi
if [ ! -f "$report_dir/index.html" ]; then
    echo "screenshot_report.sh: $report_dir/index.html: no such file" >&2
    exit 1
fi

page=$(cd "$report_dir" && pwd)/index.html
case $out in
    /*) ;;
    *) out=$(pwd)/$out ;;
esac

# A throwaway profile keeps the run from touching the user's own.
profile=$(mktemp -d "${TMPDIR:-/tmp}/screenshot_report.XXXXXX")
trap 'rm -rf "$profile"' EXIT
"$browser" --headless --disable-gpu --no-sandbox --hide-scrollbars --user-data-dir="$profile" \
    --screenshot="$out" --window-size="$size" "file://$page" >/dev/null 2>&1
if [ ! -s "$out" ]; then
    echo "screenshot_report.sh: chromium wrote no screenshot to $out" >&2
    exit 1
fi
echo "$out"
