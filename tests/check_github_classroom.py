#!/usr/bin/env python3
"""Checks the GitHub Classroom workflow that tools/github-classroom/
make_workflow.py writes into a student release (.github/workflows/
classroom.yml), as far as it can be checked without GitHub:

  1. it parses as YAML (with python3-yaml; without it, that part is skipped
     and a line-based reading of the generated layout is used instead), and
     printed without --out it is the same text;
  2. its shape: triggered on push, checks: write, one job whose graded steps
     use autograding-command-grader, and a reporter whose `runners` and
     <ID>_RESULTS variables name exactly those steps;
  3. every stage it grades exists in reference/ (has a grading.json), every
     stage with points is graded once, and each test's max-score is its
     stage's points;
  4. each stage's command, run here with the built voxlab, exits 0 for the
     reference (the same command with --submission reference/ added) and
     non-zero for the starter code in assignments/ (the command as it is);
  5. make_workflow.py --assignment courses/projections.json writes a
     workflow that grades that course's stages only, in its order, each
     worth the course's points, whose commands pass the reference and fail
     the starter code; a course naming an unknown stage is refused.

Usage: check_github_classroom.py PROJECT_SOURCE_DIR VOXLAB_BINARY
Exit: 0 passed, 1 failed.
"""
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile

COMMAND_GRADER = "classroom-resources/autograding-command-grader@"
REPORTER = "classroom-resources/autograding-grading-reporter@"
COMMAND = re.compile(r"^build/bin/voxlab check --stage (\w+)(\s.*)?$")


def load_yaml(text):
    """The parsed workflow, or None when python3-yaml is missing. Debian's
    python3 has it where the first python3 on PATH may not: try that one."""
    try:
        import yaml
    except ImportError:
        if os.path.exists("/usr/bin/python3") and os.path.realpath(sys.executable) != "/usr/bin/python3" \
                and not os.environ.get("VOXLAB_NO_REEXEC"):
            os.environ["VOXLAB_NO_REEXEC"] = "1"
            os.execv("/usr/bin/python3", ["/usr/bin/python3", *sys.argv])
        return None
    return yaml.safe_load(text)


def steps_from_yaml(doc):
    jobs = doc["jobs"]
    assert len(jobs) == 1, "one job"
    return next(iter(jobs.values()))["steps"]


def steps_from_lines(text):
    """The steps of the generated layout, read line by line (no YAML
    library): `      - key: value` starts a step, deeper `key: value` lines
    fill it, `with:` and `env:` open a mapping. Block scalars (`run: |`)
    are not read: their value is BLOCK."""
    steps, step, sub, in_steps = [], None, None, False
    for line in text.split("\n"):
        if re.match(r"^    steps:\s*$", line):
            in_steps = True
            continue
        if not in_steps or not line.strip() or line.lstrip().startswith("#"):
            continue
        m = re.match(r"^      - (\S[^:]*):\s*(.*)$", line)
        if m:
            step, sub = {}, None
            steps.append(step)
            step[m.group(1)] = unquote(m.group(2))
            continue
        m = re.match(r"^        (\S[^:]*):\s*(.*)$", line)
        if m and step is not None:
            key, value = m.group(1), m.group(2)
            if key in ("with", "env") and not value:
                sub = step[key] = {}
            else:
                sub = None
                step[key] = unquote(value)
            continue
        m = re.match(r"^          (\S[^:]*):\s*(.*)$", line)
        if m and sub is not None:
            sub[m.group(1)] = unquote(m.group(2))
    return steps


BLOCK = "(block scalar, not read)"


def unquote(v):
    v = v.strip()
    if v in ("|", ">", "|-", ">-"):
        return BLOCK
    if len(v) >= 2 and v[0] == v[-1] == '"':
        return json.loads(v)
    if re.fullmatch(r"-?\d+", v):
        return int(v)
    return v


def run_check(binary, command, extra, cwd):
    args = shlex.split(command)
    assert args[0] == "build/bin/voxlab"
    try:
        r = subprocess.run([binary, *args[1:], *extra], cwd=cwd, capture_output=True, text=True, timeout=600)
    except (OSError, subprocess.TimeoutExpired) as e:
        return None, str(e)
    return r.returncode, (r.stdout + r.stderr).strip()


def manifest_points(src):
    """Every stage's points in its reference/<stage>/grading.json."""
    reference = os.path.join(src, "reference")
    points = {}
    for stage in sorted(os.listdir(reference)):
        manifest = os.path.join(reference, stage, "grading.json")
        if os.path.isfile(manifest):
            with open(manifest, encoding="utf-8") as f:
                points[stage] = json.load(f).get("points", 0)
    return points


def check_shape(steps, expect):
    """The graded steps and the reporter that reads them; returns the graded steps."""
    graders = [s for s in steps if str(s.get("uses", "")).startswith(COMMAND_GRADER)]
    reporters = [s for s in steps if str(s.get("uses", "")).startswith(REPORTER)]
    expect(len(graders) > 0 and len(reporters) == 1, f"{len(graders)} graded steps and one reporter")
    if not graders or len(reporters) != 1:
        return []
    reporter = reporters[0]
    ids = [g.get("id") for g in graders]
    runners = [r.strip() for r in str(reporter["with"]["runners"]).split(",")]
    expect(runners == ids, "the reporter's runners are the graded steps' ids")
    env = reporter.get("env", {})
    expect(all(env.get(f"{i.upper()}_RESULTS", "").replace(" ", "") == f"${{{{steps.{i}.outputs.result}}}}"
               for i in ids) and len(env) == len(ids),
           "the reporter reads each graded step's result from <ID>_RESULTS")
    expect(steps.index(reporter) > max(steps.index(g) for g in graders), "the reporter comes after the tests")
    return graders


def check_stages(graders, wanted, expect):
    """Each graded step runs `voxlab check --stage S` worth `wanted[S]` points,
    every stage of `wanted` once, in its order; returns {stage: command}."""
    commands = {}
    for g in graders:
        w = g.get("with", {})
        m = COMMAND.match(str(w.get("command", "")))
        stage = m.group(1) if m else None
        name = g.get("id")
        expect(m is not None and stage == name and w.get("test-name") == stage,
               f"{name}: runs `voxlab check --stage {name}` as test {name}")
        if not m:
            continue
        expect(stage in wanted, f"{stage}: is one of the stages graded ({', '.join(wanted)})")
        expect(stage in wanted and float(w.get("max-score", -1)) == float(wanted[stage]) and wanted[stage] > 0,
               f"{stage}: max-score {w.get('max-score')} is the stage's points ({wanted.get(stage)})")
        timeout = w.get("timeout")
        expect(isinstance(timeout, (int, float)) and 0 < timeout <= 60, f"{stage}: timeout {timeout} minutes")
        commands[stage] = w["command"]
    expect(list(commands) == list(wanted) and len(commands) == len(graders),
           f"every stage graded once, in order ({len(wanted)} stages, {sum(wanted.values())} points)")
    return commands


def check_commands(commands, binary, reference, expect):
    """The commands: the reference passes, the starter code fails."""
    with tempfile.TemporaryDirectory(prefix="voxlab_classroom_") as tmp:
        jobs = []
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for stage, command in sorted(commands.items()):
                for who, extra in (("reference", ["--submission", reference]), ("starter code", [])):
                    cwd = os.path.join(tmp, who.replace(" ", "_"))
                    os.makedirs(cwd, exist_ok=True)
                    jobs.append((stage, who, pool.submit(run_check, binary, command, extra, cwd)))
            for stage, who, job in jobs:
                code, output = job.result()
                ok = code == 0 if who == "reference" else code not in (0, None)
                expect(ok, f"{stage}: `{commands[stage]}` exits {code} for the {who}" +
                       ("" if ok else "\n" + output[-1500:]))


def check_assignment_workflow(src, binary, expect):
    """make_workflow.py --assignment: the course's stages and points only."""
    course_file = os.path.join(src, "courses", "projections.json")
    make = os.path.join(src, "tools", "github-classroom", "make_workflow.py")
    with open(course_file, encoding="utf-8") as f:
        course = json.load(f)
    points = manifest_points(src)
    wanted = {e["stage"]: e.get("points", points[e["stage"]]) for e in course["stages"]}
    with tempfile.TemporaryDirectory(prefix="voxlab_classroom_course_") as tmp:
        out = os.path.join(tmp, "classroom.yml")
        r = subprocess.run([sys.executable, make, "--assignment", course_file, "--out", out], capture_output=True, text=True)
        expect(r.returncode == 0, "make_workflow.py --assignment courses/projections.json writes a workflow" +
               ("" if r.returncode == 0 else f" ({r.stderr.strip()})"))
        if r.returncode != 0:
            return
        text = open(out, encoding="utf-8").read()
        doc = load_yaml(text)
        steps = steps_from_yaml(doc) if doc is not None else steps_from_lines(text)
        graders = check_shape(steps, expect)
        commands = check_stages(graders, wanted, expect)
        check_commands(commands, binary, os.path.join(src, "reference"), expect)
        # A course naming a stage that does not exist is refused with its name.
        bad = os.path.join(tmp, "bad.json")
        with open(bad, "w", encoding="utf-8") as f:
            json.dump({"stages": [{"stage": "mip"}, {"stage": "mpi"}]}, f)
        r = subprocess.run([sys.executable, make, "--assignment", bad, "--out", os.path.join(tmp, "bad.yml")],
                           capture_output=True, text=True)
        expect(r.returncode != 0 and "'mpi'" in r.stderr and not os.path.exists(os.path.join(tmp, "bad.yml")),
               "a course with an unknown stage is refused, naming it" + ("" if r.returncode else " (exit 0)"))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-2])
    src, binary = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    failures = []
    # The workflow as a release gets it (tools/make_student_release.sh).
    with tempfile.TemporaryDirectory(prefix="voxlab_classroom_") as tmp:
        path = os.path.join(tmp, ".github", "workflows", "classroom.yml")
        r = subprocess.run([sys.executable, os.path.join(src, "tools", "github-classroom", "make_workflow.py"),
                            "--out", path], capture_output=True, text=True)
        if r.returncode != 0:
            print("FAIL  make_workflow.py writes the workflow: " + r.stderr.strip())
            return 1
        text = open(path, encoding="utf-8").read()

    def expect(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    # 1. YAML, and generated.
    doc = load_yaml(text)
    lines_steps = steps_from_lines(text)
    if doc is None:
        print("skip  YAML parsing: python3-yaml is not installed (apt-get install python3-yaml); "
              "reading the workflow's generated layout line by line instead")
        steps = lines_steps
    else:
        expect(isinstance(doc, dict), "classroom.yml parses as YAML")
        steps = steps_from_yaml(doc)
        on = doc.get("on", doc.get(True))  # YAML 1.1 reads a bare `on` as true
        expect(on == "push" or "push" in (on or []), "triggered on push")
        expect(doc.get("permissions", {}).get("checks") == "write", "checks: write (the reporter writes the points)")
        read = [{k: BLOCK if i < len(lines_steps) and lines_steps[i].get(k) == BLOCK else v for k, v in s.items()}
                for i, s in enumerate(steps)]
        expect(lines_steps == read, "the line-based reading (used without python3-yaml) agrees with the YAML parser")
    r = subprocess.run([sys.executable, os.path.join(src, "tools", "github-classroom", "make_workflow.py")],
                       capture_output=True, text=True)
    expect(r.returncode == 0 and r.stdout == text, "without --out, make_workflow.py prints the same workflow")

    # 2. Shape, 3. stages and points (every stage with points, in the manifests' order), 4. commands.
    graders = check_shape(steps, expect)
    if not graders:
        return 1
    points = manifest_points(src)
    order = sorted((json.load(open(os.path.join(src, "reference", s, "grading.json"))).get("order", 0), s)
                   for s, p in points.items() if p > 0)
    commands = check_stages(graders, {s: points[s] for _, s in order}, expect)
    check_commands(commands, binary, os.path.join(src, "reference"), expect)

    # 5. A course's workflow (--assignment): its stages and points only.
    check_assignment_workflow(src, binary, expect)

    print(f"{len(failures)} failure(s)" if failures else "GitHub Classroom workflow: all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
