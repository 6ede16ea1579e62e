#!/usr/bin/env bash
# Checks that the committed assignments/ is exactly what
# tools/make_assignments.py generates from reference/ (one source of truth).
# Usage: check_assignments.sh PROJECT_SOURCE_DIR
# Exit: 0 in step, 1 drifted, 77 skipped (no python3).
set -u
src_dir=${1:?usage: check_assignments.sh PROJECT_SOURCE_DIR}
if [[ -x /usr/bin/python3 ]]; then
    python=/usr/bin/python3
elif command -v python3 >/dev/null 2>&1; then
    python=python3
else
    echo "skipped: no python3 to run tools/make_assignments.py"
    exit 77
fi
exec "$python" "$src_dir/tools/make_assignments.py" --check
