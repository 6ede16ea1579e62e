#!/usr/bin/env python3
"""Checks the GitHub Classroom workflow, tools/github-classroom/classroom.yml,
as far as it can be checked without GitHub:

  1. it parses as YAML (with python3-yaml; without it, that part is skipped
     and a line-based reading of the generated layout is used instead), and
     it is what tools/github-classroom/make_workflow.py generates;
  2. its shape: triggered on push, checks: write, one job whose graded steps
     use autograding-command-grader, and a reporter whose `runners` and
     <ID>_RESULTS variables name exactly those steps;
  3. every stage it grades exists in reference/ (has a grading.json), every
     stage with points is graded once, and each test's max-score is its
     stage's points;
  4. each stage's command, run here with the built voxlab, exits 0 for the
     reference (the same command with --submission reference/ added) and
     non-zero for the starter code in assignments/ (the command as it is).

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


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-2])
    src, binary = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    path = os.path.join(src, "tools", "github-classroom", "classroom.yml")
    text = open(path, encoding="utf-8").read()
    failures = []

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
    r = subprocess.run([sys.executable, os.path.join(src, "tools", "github-classroom", "make_workflow.py"), "--check"],
                       capture_output=True, text=True)
    expect(r.returncode == 0, "classroom.yml is what make_workflow.py generates" +
           ("" if r.returncode == 0 else f" ({r.stderr.strip()})"))

    # 2. Shape.
    graders = [s for s in steps if str(s.get("uses", "")).startswith(COMMAND_GRADER)]
    reporters = [s for s in steps if str(s.get("uses", "")).startswith(REPORTER)]
    expect(len(graders) > 0 and len(reporters) == 1, f"{len(graders)} graded steps and one reporter")
    if not graders or len(reporters) != 1:
        return 1
    reporter = reporters[0]
    ids = [g.get("id") for g in graders]
    runners = [r.strip() for r in str(reporter["with"]["runners"]).split(",")]
    expect(runners == ids, "the reporter's runners are the graded steps' ids")
    env = reporter.get("env", {})
    expect(all(env.get(f"{i.upper()}_RESULTS", "").replace(" ", "") == f"${{{{steps.{i}.outputs.result}}}}"
               for i in ids) and len(env) == len(ids),
           "the reporter reads each graded step's result from <ID>_RESULTS")
    expect(steps.index(reporter) > max(steps.index(g) for g in graders), "the reporter comes after the tests")

    # 3. Stages and points.
    reference = os.path.join(src, "reference")
    points = {}
    for stage in sorted(os.listdir(reference)):
        manifest = os.path.join(reference, stage, "grading.json")
        if os.path.isfile(manifest):
            with open(manifest, encoding="utf-8") as f:
                points[stage] = json.load(f).get("points", 0)
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
        expect(stage in points, f"{stage}: reference/{stage}/grading.json exists")
        expect(stage in points and float(w.get("max-score", -1)) == float(points[stage]) and points[stage] > 0,
               f"{stage}: max-score {w.get('max-score')} is the stage's points ({points.get(stage)})")
        timeout = w.get("timeout")
        expect(isinstance(timeout, (int, float)) and 0 < timeout <= 60, f"{stage}: timeout {timeout} minutes")
        commands[stage] = w["command"]
    graded = {s for s, p in points.items() if p > 0}
    expect(sorted(commands) == sorted(graded) and len(commands) == len(graders),
           f"every stage with points is graded once ({len(graded)} stages, {sum(points.values())} points)")

    # 4. The commands: the reference passes, the starter code fails.
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

    print(f"{len(failures)} failure(s)" if failures else "GitHub Classroom workflow: all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
