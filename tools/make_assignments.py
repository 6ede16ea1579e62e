#!/usr/bin/env python3
"""Generates the student starter code, assignments/, from reference/.

One source of truth: every solution body in reference/ sits between
`// BEGIN SOLUTION` and `// END SOLUTION` lines. This tool copies reference/
to assignments/ path for path and replaces each such block with a loud stub:

  GLSL  not_implemented(); and a neutral return value: every pixel that used
        the stage shows a magenta-and-black checkerboard
        (shaders/voxlab/not_implemented.glsl);
  C++   throw NotImplemented("function"); (framework/include/io/voxlab/error.h).

Blocks between `// BEGIN WORKED EXAMPLE` and `// END WORKED EXAMPLE` are
kept (a worked example the handout walks through). Grading scenes marked "hidden" in a
stage's grading.json are left out of its generated manifest, and their scene
files are not copied: they are graded but never shipped. A stage's
mutants.json (its mutant suite, which holds solution text) is never copied.
Each stage's handout (README.md) gets, under its title, the stages it
needs: its manifest's "requires" and theirs. Every other file (scenes,
images, volumes: text or binary) is copied byte for byte. The files the
tool rewrites (.glsl, .cpp, .h, grading.json and the handouts) must be
UTF-8 text.
assignments/README.md is not generated.

    python3 tools/make_assignments.py           # (re)writes assignments/
    python3 tools/make_assignments.py --check   # exit 1 if assignments/ has drifted
    python3 tools/make_assignments.py --out DIR # the pristine starter code into DIR
                                                # (the browser page packs it: tools/setup_web.sh)
"""
import argparse
import json
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import manifest_format  # noqa: E402  (beside this script)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE = os.path.join(ROOT, "reference")
ASSIGNMENTS = os.path.join(ROOT, "assignments")
KEEP = {"README.md"}  # files of assignments/ that the tool does not own
NEVER_SHIPPED = {"mutants.json"}  # a stage's mutant suite: solution text

BEGIN = re.compile(r"^(\s*)// BEGIN SOLUTION\s*$")
END = re.compile(r"^\s*// END SOLUTION\s*$")
GLSL_SIGNATURE = re.compile(r"^(\w+)\s+(\w+)\s*\(")
CPP_SIGNATURE = re.compile(r"^[\w:<>,\s*&]*?(\w+)\s*\(")
GLSL_DEFAULTS = {"float": "0.0", "int": "0", "bool": "false", "vec2": "vec2(0.0)",
                 "vec3": "vec3(0.0)", "vec4": "vec4(0.0)", "ivec3": "ivec3(0)"}


class GeneratorError(Exception):
    pass


def cpp_parameters(lines, k):
    """The parameter names of the C++ signature that starts at line index k."""
    text = " ".join(lines[k:k + 12])
    start = text.find("(")
    depth, end = 0, start
    for end in range(start, len(text)):
        depth += {"(": 1, ")": -1}.get(text[end], 0)
        if depth == 0:
            break
    names, depth, part = [], 0, ""
    for c in text[start + 1:end] + ",":
        depth += {"<": 1, ">": -1, "(": 1, ")": -1}.get(c, 0)
        if c == "," and depth == 0:
            m = re.search(r"(\w+)\s*(\[[^\]]*\])?\s*$", part.split("=")[0])
            if m and part.strip() not in ("", "void"):
                names.append(m.group(1))
            part = ""
        else:
            part += c
    return names


def stub(lines, begin, indent, path, is_cpp):
    """The stub for the solution block starting at line index `begin`."""
    # The function's signature: the nearest line above at column 0.
    for k in range(begin - 1, -1, -1):
        line = lines[k]
        if line and not line[0].isspace() and "(" in line and not line.startswith("//"):
            break
    else:
        raise GeneratorError(f"{path}:{begin + 1}: no function signature above BEGIN SOLUTION")
    todo = f"{indent}// TODO: implement this function (see the comment above it)."
    if is_cpp:
        m = CPP_SIGNATURE.match(line)
        if not m:
            raise GeneratorError(f"{path}:{k + 1}: cannot read the function name")
        out = [todo]
        names = cpp_parameters(lines, k)
        if names:  # the stub does not read them: no "unused parameter" warnings
            out.append(f"{indent}" + ", ".join(f"(void){n}" for n in names) +
                       ";  // delete this line once you use them")
        return out + [f'{indent}throw NotImplemented("{m.group(1)}");']
    m = GLSL_SIGNATURE.match(line)
    if not m:
        raise GeneratorError(f"{path}:{k + 1}: cannot read the return type")
    out = [todo, f"{indent}not_implemented();"]
    if m.group(1) != "void":
        if m.group(1) not in GLSL_DEFAULTS:
            raise GeneratorError(f"{path}:{k + 1}: no stub value for return type {m.group(1)}")
        out.append(f"{indent}return {GLSL_DEFAULTS[m.group(1)]};")
    return out


def generate(path, text):
    """The assignment version of one reference file."""
    if not path.endswith((".glsl", ".cpp", ".h")):
        return text
    is_cpp = not path.endswith(".glsl")
    lines = text.split("\n")
    out, k = [], 0
    while k < len(lines):
        m = BEGIN.match(lines[k])
        if not m:
            if END.match(lines[k]):
                raise GeneratorError(f"{path}:{k + 1}: END SOLUTION without BEGIN")
            out.append(lines[k])
            k += 1
            continue
        end = k + 1
        while end < len(lines) and not END.match(lines[end]):
            if BEGIN.match(lines[end]):
                raise GeneratorError(f"{path}:{end + 1}: nested BEGIN SOLUTION")
            end += 1
        if end == len(lines):
            raise GeneratorError(f"{path}:{k + 1}: BEGIN SOLUTION without END")
        out.extend(stub(lines, k, m.group(1), path, is_cpp))
        k = end + 1
    header = ("// Student starter code, generated from reference/" + path +
              " by tools/make_assignments.py.\n// Implement the functions marked TODO; "
              "everything else is given.\n")
    return header + "\n".join(out)


def without_hidden_scenes(rel, text):
    """A grading manifest without its hidden scenes (graded, never shipped),
    nor the hints whose signature names one, and the paths of those scenes'
    files, which are not shipped either."""
    manifest = json.loads(text)
    scenes = manifest.get("scenes", [])
    hidden = [s for s in scenes if s.get("hidden")]
    if not hidden:
        return text, set()
    manifest["scenes"] = [s for s in scenes if not s.get("hidden")]
    names = {s["name"] for s in hidden}
    if "hints" in manifest:
        manifest["hints"] = [h for h in manifest["hints"] if not names & set(h.get("failed", []))]
    stage = os.path.dirname(rel)
    paths = {os.path.normpath(os.path.join(stage, s["scene"])) for s in hidden}
    return manifest_format.dumps(manifest), paths


def rewritten(rel):
    """Whether the tool rewrites this file (else it is copied byte for byte)."""
    return rel.endswith((".glsl", ".cpp", ".h")) or os.path.basename(rel) == "grading.json" or is_handout(rel)


def is_handout(rel):
    """A stage's handout: README.md beside its grading.json."""
    parts = rel.split(os.sep)
    return len(parts) == 2 and parts[1] == "README.md" and \
        os.path.isfile(os.path.join(REFERENCE, parts[0], "grading.json"))


def manifests():
    """Every stage's grading manifest, by stage."""
    found = {}
    for stage in sorted(os.listdir(REFERENCE)):
        path = os.path.join(REFERENCE, stage, "grading.json")
        if os.path.isfile(path):
            with open(path, encoding="utf-8") as f:
                found[stage] = json.load(f)
    return found


def prerequisites_line(stage, all_manifests):
    """The handout's header line: the stages this one needs (its manifest's
    "requires"), those they need in turn, and what happens until they are done."""
    def named(s):
        m = all_manifests.get(s, {})
        return f"`{s}` (stage {m.get('order', '?')}, {m.get('title', s)})"
    direct = all_manifests[stage].get("requires", [])
    if not direct:
        return "> **Needs:** no other stage (its grading manifest requires none).\n"
    seen, todo = list(direct), list(direct)
    while todo:
        for r in all_manifests.get(todo.pop(0), {}).get("requires", []):
            if r not in seen and r != stage:
                seen.append(r)
                todo.append(r)
    through = [s for s in seen if s not in direct]
    line = "> **Needs:** " + ", ".join(named(s) for s in direct)
    if through:
        line += "; through them also " + ", ".join(f"`{s}`" for s in through)
    return (line + ".\n> Until those are done, their magenta checkerboard covers this stage's scenes: "
            "`voxlab check` reports such a scene as \"blocked by\" the missing function and grades "
            "only what runs your code (docs/grading.md).\n")


def with_prerequisites(rel, text, all_manifests):
    """The handout with its prerequisites under its title (the first line)."""
    stage = rel.split(os.sep)[0]
    first, _, rest = text.partition("\n")
    return first + "\n\n" + prerequisites_line(stage, all_manifests) + rest


def expected_files():
    """Every file of assignments/ the tool owns, as its exact bytes."""
    files, hidden = {}, set()
    all_manifests = manifests()
    for folder, _, names in os.walk(REFERENCE):
        for name in sorted(names):
            if name in NEVER_SHIPPED:
                continue
            full = os.path.join(folder, name)
            rel = os.path.relpath(full, REFERENCE)
            with open(full, "rb") as f:
                data = f.read()
            if not rewritten(rel):
                files[rel] = data  # a handout, a scene, an image, a volume: as it is
                continue
            try:
                # Universal newlines, as before: the generated file has \n line ends.
                text = data.decode("utf-8").replace("\r\n", "\n").replace("\r", "\n")
            except UnicodeDecodeError as e:
                raise GeneratorError(f"reference/{rel}: not UTF-8 text ({e.reason} at byte {e.start})")
            if name == "grading.json":
                text, paths = without_hidden_scenes(rel, text)
                hidden |= paths
            if is_handout(rel):
                text = with_prerequisites(rel, text, all_manifests)
            files[rel] = generate(rel, text).encode("utf-8")
    for rel in hidden:
        files.pop(rel, None)
    return files


def existing_files():
    found = set()
    for folder, _, names in os.walk(ASSIGNMENTS):
        for name in names:
            rel = os.path.relpath(os.path.join(folder, name), ASSIGNMENTS)
            if rel not in KEEP:
                found.add(rel)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="report drift instead of writing")
    parser.add_argument("--out", metavar="DIR", help="write the starter code into DIR (with assignments/README.md) "
                                                     "instead of assignments/")
    args = parser.parse_args()
    try:
        files = expected_files()
    except GeneratorError as e:
        sys.exit(f"make_assignments: {e}")
    if args.out:  # a pristine copy elsewhere: the generated files and the README the tool leaves alone
        for rel, data in list(files.items()) + [(k, open(os.path.join(ASSIGNMENTS, k), "rb").read()) for k in KEEP]:
            path = os.path.join(args.out, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(data)
        print(f"wrote {len(files) + len(KEEP)} files to {args.out}")
        return
    stale = sorted(existing_files() - set(files))
    if args.check:
        problems = [f"assignments/{rel}: not in reference/ (remove it)" for rel in stale]
        for rel, data in sorted(files.items()):
            path = os.path.join(ASSIGNMENTS, rel)
            if not os.path.exists(path):
                problems.append(f"assignments/{rel}: missing")
            else:
                with open(path, "rb") as f:
                    if f.read() != data:
                        problems.append(f"assignments/{rel}: differs from what reference/{rel} generates")
        for p in problems:
            print(p, file=sys.stderr)
        if problems:
            print("make_assignments: assignments/ has drifted: run python3 tools/make_assignments.py",
                  file=sys.stderr)
            sys.exit(1)
        print(f"assignments/ matches reference/ ({len(files)} files)")
        return
    for rel in stale:
        os.remove(os.path.join(ASSIGNMENTS, rel))
    for rel, data in files.items():
        path = os.path.join(ASSIGNMENTS, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
    print(f"wrote {len(files)} files to assignments/")


if __name__ == "__main__":
    main()
