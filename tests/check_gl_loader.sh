#!/usr/bin/env bash
# Checks that the committed framework/gl/voxlab_gl.{h,c} match what
# tools/gen_gl_loader.py produces from the installed Khronos gl.xml.
# Usage: check_gl_loader.sh PROJECT_SOURCE_DIR
# Exit: 0 up to date, 1 stale (or generator failure), 77 skipped (CTest).
set -u

src_dir=${1:?usage: check_gl_loader.sh PROJECT_SOURCE_DIR}
xml=/usr/share/khronos-api/gl.xml

if [[ ! -f $xml ]]; then
    echo "skipped: $xml not found (install the khronos-api package)"
    exit 77
fi

if [[ -x /usr/bin/python3 ]]; then
    python=/usr/bin/python3
elif command -v python3 >/dev/null 2>&1; then
    python=python3
else
    echo "skipped: no python3 to run tools/gen_gl_loader.py"
    exit 77
fi

tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT

if ! "$python" "$src_dir/tools/gen_gl_loader.py" --xml "$xml" --out "$tmp" >"$tmp/gen.log" 2>&1; then
    echo "tools/gen_gl_loader.py failed:"
    cat "$tmp/gen.log"
    exit 1
fi

status=0
: >"$tmp/diff"
for f in voxlab_gl.h voxlab_gl.c; do
    diff -u "$src_dir/framework/gl/$f" "$tmp/$f" >>"$tmp/diff" 2>&1 || status=1
done

if [[ $status -ne 0 ]]; then
    echo "framework/gl is stale: run tools/gen_gl_loader.py"
    head -n 40 "$tmp/diff"
    exit 1
fi
echo "gl loader up to date"
exit 0
