#!/usr/bin/env bash
# Builds the student release of voxlab: everything a student needs and
# nothing of the reference solution.
#
#   tools/make_student_release.sh OUT_DIR
#
# OUT_DIR receives the framework, shaders, the starter code (assignments/,
# with every stage's handout, grading scenes and manifest), the datasets,
# the docs, tools/setup.sh and tools/nrrd_to_dicom.py, and expected/: the golden outputs of every
# grading scene and function check, rendered here from reference/, which
# `voxlab check` compares a student's work with. reference/, the tests and
# bench/ are left out (they hold or use the solution); of tests/ only the
# golden scenes go along, since the handouts render them. The script then
# checks that no solution text went along: no BEGIN SOLUTION marker, and no
# three consecutive lines of a solution block in any shipped file; and that
# no hidden grading scene went along (its scene file or its golden image).
# Every shipped Markdown file is its student text (tools/student_text.py):
# blocks marked for instructors are removed, those marked for students shown,
# instructor-only files left out (docs/courses.md, docs/instructors.md, ...);
# the release fails if instructor material (build/tests, VOXLAB_STAGE_ROOT,
# the generator, drift tests, the mutant suite and calibration, running a
# course) is left in it, or if a link points at a file it does not ship
# (reference/, an instructor-only page).
# It prints one line as each step starts and one with its time as it ends.
# On 2 cores: about 4.5 minutes when voxlab has to be built from scratch,
# 12 s when the build folder is up to date (10 s of it rendering expected/).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out="${1:?usage: tools/make_student_release.sh OUT_DIR}"
build="${VOXLAB_BUILD_DIR:-$root/build}"
if [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
  echo "make_student_release: $out exists and is not empty" >&2
  exit 2
fi

# Progress: `step N TEXT` ends the previous step, printing its time, and
# starts step N of $steps; `step done` ends the last one.
steps=6
step_number=0 step_text="" step_start=0 release_start=$(date +%s%N)
seconds_since() { awk -v a="$1" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }'; }
step() {
  if [ "$step_number" -gt 0 ]; then
    echo "release: [$step_number/$steps] done in $(seconds_since "$step_start") s"
  fi
  [ "$1" = done ] && return
  step_number=$1 step_text=$2 step_start=$(date +%s%N)
  echo "release: [$step_number/$steps] $step_text"
}
trap 'echo "make_student_release: failed in step $step_number/$steps ($step_text)" >&2' ERR

# The starter code must match the reference it is generated from.
step 1 "checking that assignments/ matches reference/"
python3 "$root/tools/make_assignments.py" --check >/dev/null

step 2 "building voxlab in $build (minutes, unless it is up to date)"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target voxlab >/dev/null

step 3 "copying the framework, shaders, starter code, datasets and docs to $out"
mkdir -p "$out"
for item in CMakeLists.txt framework shaders assignments datasets docs; do
  cp -r "$root/$item" "$out/"
done
# The stages' oracle tests stay in the repository (a release has no tests/
# to build them, and an oracle spells out the technique a student writes).
rm -f "$out"/framework/stages/*/test_*.cpp
mkdir -p "$out/tools"
cp "$root/tools/setup.sh" "$out/tools/"
cp "$root/tools/nrrd_to_dicom.py" "$out/tools/"   # a DICOM series from a dataset (datasets/README.md)
cp "$root/README.md" "$out/README_framework.md"   # the framework's full guide
cat > "$out/README.md" <<'MD'
# voxlab (student release)

voxlab is a framework for learning volume rendering: you write the renderer's stages (sampling,
MIP, compositing, isosurfaces, gradients, shading, transfer functions, texture slicing) as small
GLSL and C++ functions; the framework does the rest.

On Debian 12:

```sh
tools/setup.sh                 # installs what is missing, builds, opens the viewer (or renders headless)
```

- **Your work** is in `assignments/`, one folder per stage, each with its handout (`README.md`).
  Start with `assignments/README.md`. A stage you have not done shows a magenta checkerboard.
- **Look at it:** `build/bin/voxlab view` (H lists the keys; R or saving a shader reloads it),
  or `build/bin/voxlab render assignments/mip/scenes/bonsai_oblique.json --out mine.png`.
- **Compare it** in the viewer: open a grading scene (`build/bin/voxlab view
  assignments/mip/scenes/bonsai_oblique.json`) and press S: the split view and the difference
  (S again) show your image against the expected one, the scene as graded.
- **Check it** the way it will be graded: `build/bin/voxlab check --stage mip`, then open
  `voxlab-check/index.html`. How grading works: `docs/grading.md`.
- **C++ stages** (the folders of `assignments/` with a `.cpp` file) are compiled into `voxlab`: rebuild with
  `cmake --build build` after editing them (`voxlab check` compiles them itself).
- The framework's full guide (conventions, scene files, datasets, renderers, the viewer):
  `README_framework.md`.
MD
# The GitHub Classroom autograding workflow for this release's stages
# (tools/github-classroom/README.md), and what students' commits leave out.
mkdir -p "$out/.github/workflows"
python3 "$root/tools/github-classroom/make_workflow.py" --out "$out/.github/workflows/classroom.yml" >/dev/null
printf '/build/\n/voxlab-check/\n' > "$out/.gitignore"
mkdir -p "$out/tests/golden"   # the scenes the handouts render (JSON only)
cp -r "$root/tests/golden/scenes" "$out/tests/golden/"

# What students read: the handouts, READMEs and docs without instructor material.
step 4 "turning the Markdown into its student text (tools/student_text.py)"
python3 "$root/tools/student_text.py" --release "$out" >/dev/null

# The expected outputs, rendered by the reference on this machine.
step 5 "rendering expected/ with the reference (every stage's scenes and checks)"
LP_NUM_THREADS="${LP_NUM_THREADS:-2}" "$build/bin/voxlab" grade --render-expected "$out/expected" --quiet >/dev/null

# No solution may leak: no mutant suite (its substitutions quote the solution),
# no markers, and no non-trivial solution line.
step 6 "checking that no solution text and no hidden scene was shipped"
if find "$out" -name mutants.json | grep -q .; then
  echo "make_student_release: a stage's mutants.json was shipped:" >&2
  find "$out" -name mutants.json >&2
  exit 1
fi

if [ -n "$(find "$out" -name "*.so" -print -quit)" ]; then
  echo "make_student_release: a compiled library was shipped (the reference's C++ stages are the solution):" >&2
  find "$out" -name "*.so" >&2
  exit 1
fi

if grep -rl "BEGIN SOLUTION" "$out" >/dev/null; then
  echo "make_student_release: a solution marker was shipped:" >&2
  grep -rl "BEGIN SOLUTION" "$out" >&2
  exit 1
fi
python3 - "$root/reference" "$out" <<'PY'
import os, re, sys
reference, out = sys.argv[1], sys.argv[2]
# Every run of three consecutive lines of a solution block. One
# line alone may be generic ("return ray.t_exit > ray.t_entry;" is also
# framework code); three in a row are the solution.
def lines_of(path):
    # Lines of punctuation alone ("}", "});") say nothing about a solution.
    return [l.strip() for l in open(path, errors="replace") if len(re.sub(r"\W", "", l)) >= 2]
# Nor do lines that only set or return a constant ("t = 0.0;", "return false;"):
# three of them in a row are the "nothing found" ending of any search, the
# framework's own included (voxlab/runs.glsl), not a solution.
CONSTANT = r"(-?\d+(\.\d*)?|true|false|[iu]?vec[234]\(-?[\d.]+\))"
def constant_only(line):
    return re.fullmatch(r"([\w.\[\]]+\s*=\s*|return\s+)?" + CONSTANT + r"?\s*;", line) is not None
runs = set()
for d, _, files in os.walk(reference):
    for f in files:
        block, inside = [], False
        for line in lines_of(os.path.join(d, f)):
            if re.match(r"// BEGIN SOLUTION", line): inside, block = True, []; continue
            if re.match(r"// END SOLUTION", line):
                inside = False
                runs.update(tuple(block[i:i + 3]) for i in range(len(block) - 2)
                            if not all(constant_only(l) for l in block[i:i + 3]))
                continue
            if inside: block.append(line)
leaks = []
for d, _, files in os.walk(out):
    for f in files:
        if not f.endswith((".glsl", ".cpp", ".h", ".frag", ".vert", ".md", ".json")): continue
        text = lines_of(os.path.join(d, f))
        for i in range(len(text) - 2):
            if tuple(text[i:i + 3]) in runs: leaks.append(f"{os.path.join(d, f)}: {text[i]}")
if leaks:
    print("make_student_release: solution lines were shipped:", *leaks[:20], sep="\n", file=sys.stderr)
    sys.exit(1)
# Hidden grading scenes stay with the instructor: no scene file, no golden image.
import json
shipped = []
for stage in sorted(os.listdir(reference)):
    manifest = os.path.join(reference, stage, "grading.json")
    if not os.path.isfile(manifest): continue
    for scene in json.load(open(manifest)).get("scenes", []):
        if not scene.get("hidden"): continue
        for path in (os.path.join(out, "assignments", stage, scene["scene"]),
                     os.path.join(out, "expected", stage, scene["name"] + ".png")):
            if os.path.exists(path): shipped.append(path)
if shipped:
    print("make_student_release: hidden grading scenes were shipped:", *shipped, sep="\n", file=sys.stderr)
    sys.exit(1)
PY
step done
echo "release: $(seconds_since "$release_start") s in all"
echo "student release: $out ($(du -sh "$out" | cut -f1)); build it with tools/setup.sh, check work with voxlab check"
