#!/usr/bin/env bash
# The Gradescope path, run locally: tools/gradescope/run_autograder with
# VOXLAB_AUTOGRADER_ROOT pointing at a temporary /autograder, an assignment
# file (courses/projections.json: mip 10 points, minip 5) and Gradescope's
# submission metadata. One submission, with a real mistake in mip (the loop
# starts at sample 1, so its scores are fractions), is uploaded the ways
# students upload: the proper layout, loose files, a nested release folder,
# a zip of that, and the assignments/ folder itself. Each must score the
# same. results.json must follow the assignment's visibility, its test
# scores must add up to the total exactly, and a submission two days late
# loses the file's 10 % a day. A zip with an entry that climbs out with
# "../" is refused as a whole (voxlab unpacks zips, not Python): it writes
# nothing outside, and its results.json scores 0 and says why.
#
# usage: check_gradescope_path.sh PROJECT_DIR VOXLAB_BINARY
set -euo pipefail
project=$1
bin=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

student="$work/student"
mkdir -p "$student/mip" "$student/minip"
cp "$project/reference/minip/minip.glsl" "$student/minip/"
sed 's/for (int m = 0; m < n; ++m)/for (int m = 1; m < n; ++m)/' "$project/reference/mip/mip.glsl" > "$student/mip/mip.glsl"
grep -q 'int m = 1; m < n' "$student/mip/mip.glsl" || { echo "FAIL: the mistake was not applied"; exit 1; }

# grade LAYOUT CREATED_AT NAME: prepares the upload in $work/root/submission,
# runs the autograder and keeps its results.json as $work/NAME.json.
grade() {
  local layout=$1 created=$2 name=$3 root="$work/root"
  rm -rf "$root" && mkdir -p "$root/source" "$root/submission"
  cp "$project/courses/projections.json" "$root/source/assignment.json"
  printf '{"created_at": "%s", "assignment": {"due_date": "2026-12-01T23:59:00.000000+01:00"}}\n' "$created" \
    > "$root/submission_metadata.json"
  local s="$root/submission"
  case "$layout" in
    proper) cp -r "$student/mip" "$student/minip" "$s/" ;;
    loose) cp "$student/mip/mip.glsl" "$student/minip/minip.glsl" "$s/" ;;
    nested) mkdir -p "$s/voxlab-student/assignments" && cp -r "$student/mip" "$student/minip" "$s/voxlab-student/assignments/" ;;
    assignments) mkdir -p "$s/assignments" && cp -r "$student/mip" "$student/minip" "$s/assignments/" ;;
    zip|zip_climb)
         rm -rf "$work/z" && mkdir -p "$work/z/voxlab-student/assignments"
         cp -r "$student/mip" "$student/minip" "$work/z/voxlab-student/assignments/"
         (cd "$work/z" && python3 -c 'import sys, zipfile, os
with zipfile.ZipFile(sys.argv[1], "w") as z:
    for d, _, fs in os.walk("."):
        for f in fs: z.write(os.path.join(d, f))
    if sys.argv[2] == "zip_climb": z.writestr("../../climbed_out.txt", "outside")' "$s/upload.zip" "$layout") ;;
  esac
  VOXLAB_AUTOGRADER_ROOT="$root" VOXLAB_AUTOGRADER_VOXLAB="$project" VOXLAB_AUTOGRADER_BIN="$bin" \
    bash "$project/tools/gradescope/run_autograder" > "$work/$name.log" 2>&1
  cp "$root/results/results.json" "$work/$name.json"
  if [ -e "$work/climbed_out.txt" ] || [ -e "$root/climbed_out.txt" ]; then
    echo "FAIL: a zip entry was written outside the upload"; exit 1
  fi
}

# Without a voxlab program (a checkout built elsewhere, VOXLAB_AUTOGRADER_BIN
# not set) the autograder fails loudly: exit 1, the reason on stderr, never
# a quiet score of 0.
mkdir -p "$work/unbuilt/source" "$work/unbuilt/submission" "$work/unbuilt_checkout"
cp "$student/mip/mip.glsl" "$work/unbuilt/submission/"
if VOXLAB_AUTOGRADER_ROOT="$work/unbuilt" VOXLAB_AUTOGRADER_VOXLAB="$work/unbuilt_checkout" \
     bash "$project/tools/gradescope/run_autograder" > "$work/unbuilt.log" 2>&1; then
  echo "FAIL: run_autograder without a voxlab program exited 0:"; cat "$work/unbuilt.log"; exit 1
fi
grep -q "VOXLAB_AUTOGRADER_BIN" "$work/unbuilt.log" || { echo "FAIL: the failure does not say what to set:"; cat "$work/unbuilt.log"; exit 1; }

for layout in proper loose nested assignments zip zip_climb; do grade "$layout" 2026-12-01T12:00:00Z "$layout"; done
grade proper 2026-12-03T10:00:00+00:00 late

python3 - "$work" <<'EOF'
import json, sys
work = sys.argv[1]
load = lambda name: json.load(open(f"{work}/{name}.json"))
proper = load("proper")
problems = []
def check(ok, what):
    if not ok: problems.append(what)
cents = lambda x: round(x * 100)
tests = proper["tests"]
check(len(tests) == 14, f"14 tests expected (6+1 mip, 6+1 minip), got {len(tests)}")
check(sum(cents(t["max_score"]) for t in tests) == 1500, "the tests' max_score must add up to exactly 15.00")
check(sum(cents(t["score"]) for t in tests) == cents(proper["score"]), "the tests' scores must add up to the total")
check(0 < proper["score"] < 15, f"the mistake in mip must cost points but not all: {proper['score']}")
minip = [t for t in tests if t["name"].startswith("Minimum")]
check(sum(cents(t["score"]) for t in minip) == 500, "minip is correct: 5.00 of 5")
vis = {t["name"].split(": ", 1)[1] + "@" + t["name"][:3]: t["visibility"] for t in tests}
check(vis.get("minip_random_rays@Min") == "hidden", "the assignment hides minip_random_rays")
check(vis.get("ct_signed_core@Min") == "after_due_date", "a hidden scene shows after the due date")
check(vis.get("ct_signed_air@Max") == "after_due_date", "a hidden scene shows after the due date")
check(vis.get("bonsai_oblique@Max") == "visible", "other tests are visible")
key = lambda r: [(t["name"], t["score"], t["max_score"], t["visibility"]) for t in r["tests"]]
for layout in ["loose", "nested", "assignments", "zip"]:
    r = load(layout)
    check(r["score"] == proper["score"] and key(r) == key(proper),
          f"{layout}: scored {r['score']}, unlike the proper layout's {proper['score']}")
climb = load("zip_climb")
check(climb["score"] == 0 and "climbs out" in climb["output"] + json.dumps(climb["tests"]),
      f"a zip with a ../ entry is refused with its reason: {climb['score']}, {climb['output'][:200]}")
late = load("late")
check(abs(late["score"] - round(proper["score"] * 0.8, 2)) < 0.006,
      f"two days late at 10 %/day: {late['score']} should be 0.8 x {proper['score']}")
check("late" in late["output"].lower(), "the output says the submission was late")
if problems:
    print("FAIL:\n  " + "\n  ".join(problems))
    sys.exit(1)
print(f"ok: {proper['score']} / 15 in every layout; late {late['score']}")
EOF
