#!/usr/bin/env bash
# voxlab's parsers under libFuzzer, for long runs.
#
#   tools/fuzz.sh [RUNS [TARGET...]]
#
# Builds the fuzz targets of tests/fuzz/ with clang in $VOXLAB_BUILD_DIR/fuzz
# (the folder the main build's sub-build uses), then runs each TARGET (default:
# tests/fuzz/targets.cmake's VOXLAB_FUZZ_TARGETS but dicom, docs/fuzzing.md) for RUNS
# executions (default 1000000), one after the other, and prints a table of
# executions, wall time and findings. New inputs are kept in
# $VOXLAB_BUILD_DIR/fuzz/work/TARGET, so later runs start from them; inputs
# that found something are in $VOXLAB_BUILD_DIR/fuzz/artifacts/. Extra
# libFuzzer options go in $VOXLAB_FUZZ_OPTIONS (e.g. "-seed=7 -jobs=2").
#
# Environment: VOXLAB_BUILD_DIR (default: build), VOXLAB_FUZZ_CXX (default:
# clang++-14, else clang++), VOXLAB_JOBS (build jobs, default 2).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${VOXLAB_BUILD_DIR:-$root/build}"
fuzz="$build/fuzz"
runs="${1:-1000000}"
[ $# -gt 0 ] && shift
case "$runs" in
  -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
  *[!0-9]*|'') echo "fuzz.sh: RUNS must be a number, got '$runs'" >&2; exit 2 ;;
esac
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  # shellcheck disable=SC2207  # one word per target
  targets=($(awk '/^set\(VOXLAB_FUZZ_TARGETS/ { on = 1; next }
                  on { sub(/#.*/, ""); gsub(/\)/, " ) ");
                       for (i = 1; i <= NF; i++) { if ($i == ")") exit; if ($i != "dicom") print $i } }' "$root/tests/fuzz/targets.cmake"))
fi

cxx="${VOXLAB_FUZZ_CXX:-$(command -v clang++-14 || command -v clang++ || true)}"
[ -n "$cxx" ] || { echo "fuzz.sh: clang++ not found (Debian: apt-get install clang)" >&2; exit 2; }
cmake -S "$root/tests/fuzz" -B "$fuzz" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$fuzz" -j "${VOXLAB_JOBS:-2}"

summary=()
failed=0
for t in "${targets[@]}"; do
  [ -x "$fuzz/fuzz_$t" ] || { echo "fuzz.sh: no target '$t'" >&2; exit 2; }
  log="$fuzz/logs/$t.log"
  mkdir -p "$fuzz/logs"
  echo "== fuzz_$t: $runs executions (log: $log)"
  start=$(date +%s.%N)
  status=0
  # shellcheck disable=SC2086  # VOXLAB_FUZZ_OPTIONS is a list of options
  VOXLAB_FUZZ_WORK="$fuzz/work/$t" "$root/tests/fuzz/run_fuzzer.sh" "$fuzz/fuzz_$t" \
    "$fuzz/corpus/$t" "$runs" ${VOXLAB_FUZZ_OPTIONS:-} >"$log" 2>&1 || status=$?
  end=$(date +%s.%N)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.0f", b - a }')
  result=ok
  if [ "$status" -ne 0 ]; then
    result="FINDING (exit $status, see $log)"
    failed=1
    grep -E "voxlab fuzz finding|ERROR: |runtime error|SUMMARY" "$log" | head -5 || true
  fi
  summary+=("$(printf '%-15s %10s execs %7s s %7s execs/s  %s' "$t" "${execs:-?}" "$seconds" "${rate:-?}" "$result")")
done

echo
echo "tools/fuzz.sh $runs  ($(date -u +%Y-%m-%dT%H:%M:%SZ), $(nproc) cores)"
printf '%s\n' "${summary[@]}"
exit "$failed"
