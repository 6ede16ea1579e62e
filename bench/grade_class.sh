#!/usr/bin/env bash
# Times grading a class of 10 submissions with `voxlab grade --batch`.
#
#   bench/grade_class.sh [JOBS] [OUT_DIR]
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
voxlab="${VOXLAB_BUILD_DIR:-$root/build}/bin/voxlab"
class="$out/class"
mkdir -p "$class"

/usr/bin/env python3 - "$root" "$class" <<'PY'
import json, os, random, shutil, sys
root, class_dir = sys.argv[1], sys.argv[2]
mutants = [m for stage in sorted(os.listdir(os.path.join(root, "reference")))
           if os.path.exists(os.path.join(root, "reference", stage, "mutants.json"))
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
for k in range(2, 10):
    by_stage = {}
    for m in rng.sample(mutants, 3):
        by_stage.setdefault(m["stage"], m)  # one bug per stage
    stubs = rng.sample(["tf2d", "cutting_plane", "texslice2d", "texslice3d"], 2) if k in (8, 9) else []
    student(f"s{k:02d}", [m for s, m in by_stage.items() if s not in stubs], stubs)
PY

start=$(date +%s.%N)
"$voxlab" grade --batch "$class" --out "$out/reports" --jobs "$jobs" --quiet
end=$(date +%s.%N)
echo
python3 -c "print(f'grading 10 submissions with --jobs $jobs took {$end - $start:.1f} s')"
echo "gradebook: $out/reports/gradebook.csv; class report: $out/reports/index.html"
