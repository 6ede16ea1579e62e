#!/usr/bin/env bash
# Grades the reference through EGL on a GPU against expected outputs
# rendered elsewhere (llvmpipe), and prints per stage its score and the
# worst tolerance ratio (bench/grade_summary.py): whether the grader's
# verdicts hold on this GL.
#
#   bench/gpu_check.sh EXPECTED [JOBS] [OUT]
#
# EXPECTED: `voxlab grade --render-expected EXPECTED --with-hidden` made on
# the machine whose verdicts are the calibration (llvmpipe). JOBS: stages
# graded at once (default 1). OUT: the report folder (default
# /tmp/voxlab-gpu-check). GL=osmesa grades on this machine's OSMesa instead
# (GALLIUM_DRIVER=softpipe for Mesa's softpipe, with TIME_LIMIT=600: each
# stage's time limit in seconds, default 60), the same check on a CPU.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
voxlab="${VOXLAB:-$root/build/bin/voxlab}"
expected="${1:?usage: bench/gpu_check.sh EXPECTED [JOBS] [OUT]}"
jobs="${2:-1}"
out="${3:-/tmp/voxlab-gpu-check}"
start=$(date +%s.%N)
VOXLAB_GL="${GL:-egl}" "$voxlab" grade --submission "$root/reference" --expected "$expected" --jobs "$jobs" \
  --time-limit "${TIME_LIMIT:-60}" --out "$out" --quiet >/dev/null || true
end=$(date +%s.%N)
python3 -c 'import sys; print("graded in %.1f s with --jobs %s" % (float(sys.argv[2]) - float(sys.argv[1]), sys.argv[3]))' \
  "$start" "$end" "$jobs"
python3 "$root/bench/grade_summary.py" "$out"
