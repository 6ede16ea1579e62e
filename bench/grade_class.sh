#!/usr/bin/env bash
# Times grading a class with `voxlab grade --batch`.
#
#   bench/grade_class.sh [JOBS] [OUT_DIR] [STUDENTS] [ASSIGNMENT]
#
# STUDENTS (default 10) submissions; ASSIGNMENT: a courses/*.json file whose
# stages are graded (default: every stage).
#
# The class is synthetic but realistic: the reference solution, the pristine
# starter code, and eight students each with a few of the mutants of
# reference/<stage>/mutants.json (realistic bugs) in otherwise correct work, two
# of them with unfinished stages left as stubs. Prints the wall time and the
# gradebook. JOBS defaults to the CPU count.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs="${1:-$(nproc)}"
out="${2:-$(mktemp -d /tmp/voxlab_class.XXXXXX)}"
students="${3:-10}"
assignment="${4:-}"
voxlab="${VOXLAB_BUILD_DIR:-$root/build}/bin/voxlab"
class="$out/class"
mkdir -p "$class"

/usr/bin/env python3 - "$root" "$class" "$students" "$assignment" <<'PY'
import json, os, random, shutil, sys
root, class_dir, count, assignment = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
graded = [s["stage"] for s in json.load(open(assignment))["stages"]] if assignment else None
mutants = [m for stage in sorted(os.listdir(os.path.join(root, "reference")))
           if os.path.exists(os.path.join(root, "reference", stage, "mutants.json"))
           and (graded is None or stage in graded)
           for m in json.load(open(os.path.join(root, "reference", stage, "mutants.json"))).get("mutants", [])]
rng = random.Random(2026)
def student(name, bugs=(), stubs=()):
    folder = os.path.join(class_dir, name)
    shutil.copytree(os.path.join(root, "reference"), folder)
    for stage in stubs:  # unfinished: the starter code's stubs
        shutil.rmtree(os.path.join(folder, stage))
        shutil.copytree(os.path.join(root, "assignments", stage), os.path.join(folder, stage))
    for m in bugs:
        path = os.path.join(folder, m["file"])
        text = open(path).read()
        open(path, "w").write(text.replace(m["find"], m["replace"], 1))
student("s00_reference")
shutil.copytree(os.path.join(root, "assignments"), os.path.join(class_dir, "s01_pristine"))
for k in range(2, count):
    by_stage = {}
    for m in rng.sample(mutants, min(3, len(mutants))):
        by_stage.setdefault(m["stage"], m)  # one bug per stage
    unfinished = [s for s in ["tf2d", "cutting_plane", "texslice2d", "texslice3d"] if graded is None or s in graded]
    stubs = rng.sample(unfinished, min(2, len(unfinished))) if k % 10 in (8, 9) else []
    student(f"s{k:02d}", [m for s, m in by_stage.items() if s not in stubs], stubs)
PY

options=()
[ -n "$assignment" ] && options=(--assignment "$assignment")
"$voxlab" grade --prepare --quiet >/dev/null  # the reference's images, once (the expected-output cache)
start=$(date +%s.%N)
"$voxlab" grade --batch "$class" --out "$out/reports" --jobs "$jobs" --quiet "${options[@]}"
end=$(date +%s.%N)
echo
/usr/bin/python3 -c "t = $end - $start; print(f'grading $students submissions ({\"$assignment\" or \"every stage\"}) with --jobs $jobs took {t:.1f} s, {t / $students:.2f} s a submission')"
echo "gradebook: $out/reports/gradebook.csv; class report: $out/reports/index.html"
