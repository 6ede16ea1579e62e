#!/usr/bin/env bash
# Runs one voxlab fuzz target for a number of executions.
#
#   tests/fuzz/run_fuzzer.sh FUZZER SEEDS RUNS [LIBFUZZER_OPTION...]
#
# FUZZER is a built target (build/fuzz/fuzz_NAME), SEEDS its seed corpus
# (build/fuzz/corpus/NAME), RUNS the number of executions (the seeds
# included). New inputs go to a fresh temporary folder, so the seeds are
# never changed, unless VOXLAB_FUZZ_WORK names a folder to keep them in
# (tools/fuzz.sh). A finding (fuzz_common.h) stops the run with a non-zero
# exit; the input that caused it is saved in VOXLAB_FUZZ_ARTIFACTS (default:
# artifacts/ beside the fuzzer) and replayed by `FUZZER ARTIFACT`.
#
# The dictionary tests/fuzz/dict/NAME.dict (field names, keywords, escapes)
# is passed when it exists.
#
# Limits: 10 s per input (a hang), 512 MiB in one allocation and 2 GiB
# resident (a size taken from the input and trusted), inputs up to 8 KiB.
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,19p' "$0" >&2
  exit 2
fi
fuzzer=$1 seeds=$2 runs=$3
shift 3
name=$(basename "$fuzzer")
artifacts="${VOXLAB_FUZZ_ARTIFACTS:-$(dirname "$fuzzer")/artifacts}"
mkdir -p "$artifacts"
if [ -n "${VOXLAB_FUZZ_WORK:-}" ]; then
  work=$VOXLAB_FUZZ_WORK
  mkdir -p "$work"
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/voxlab_${name}_XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi
[ -d "$seeds" ] || { echo "$name: no seed corpus at $seeds" >&2; exit 2; }

dict=()
dictionary="$(dirname "${BASH_SOURCE[0]}")/dict/${name#fuzz_}.dict"
[ -f "$dictionary" ] && dict=(-dict="$dictionary")

status=0
"$fuzzer" "${dict[@]}" -runs="$runs" -max_len=8192 -timeout=10 -malloc_limit_mb=512 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$artifacts/$name-" "$@" "$work" "$seeds" || status=$?
if [ "$status" -ne 0 ]; then
  echo "$name: FINDING (exit $status); the input is in $artifacts/ (replay: $fuzzer FILE)" >&2
fi
exit "$status"
