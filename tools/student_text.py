#!/usr/bin/env python3
"""The student text of voxlab's Markdown: one source for two audiences.

The handouts (reference/<stage>/README.md, copied to assignments/), the
README files and docs/ are written once, for the full repository, with
blocks marked for one audience. Each marker is a line of its own, outside
code blocks:

  <!-- instructor -->        shown in the full repository; the block, markers
  ...                       included, is removed from the student release
  <!-- /instructor -->      (oracle tests under build/tests, the generator,
                            cmake -DVOXLAB_STAGE_ROOT, drift tests, ...)

  <!-- student              an HTML comment in the full repository, so not
  ...                       shown there; in the student release its lines
  -->                       are shown and the two marker lines removed

  <!-- instructor-only file -->   as a file's first line: the whole file is
                                  left out of the student release

tools/make_student_release.sh runs `--release OUT` on what it shipped: every
Markdown file becomes its student text, and the release fails if instructor
material is left in it (build/tests, VOXLAB_STAGE_ROOT, drift tests, the
mutant suite, calibration, running a course, ...) or if a link points at a
file the release does not have (reference/, an instructor-only page).
The test student_text (tests/CMakeLists.txt) runs `--check ROOT` on the
Markdown a release ships, without building one.

    python3 tools/student_text.py --check [ROOT]     # the source tree (default: this checkout)
    python3 tools/student_text.py --print FILE       # one file's student text, to read it
    python3 tools/student_text.py --release OUT      # rewrite a release in place, then check it
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

INSTRUCTOR_BEGIN = "<!-- instructor -->"
INSTRUCTOR_END = "<!-- /instructor -->"
STUDENT_BEGIN = "<!-- student"
STUDENT_END = "-->"
INSTRUCTOR_FILE = "<!-- instructor-only file -->"

# What a student in the release cannot use or need not know: the tests and
# their build folder, the generator and its drift test, the C++ stage root,
# the reference solution's folder, and the markers themselves.
FORBIDDEN = [
    (re.compile(r"build/tests"), "the test binaries (build/tests/) are not in the release"),
    (re.compile(r"\bctest\b"), "the release has no tests"),
    (re.compile(r"VOXLAB_STAGE_ROOT"), "the release builds assignments/ in; no stage root to choose"),
    (re.compile(r"VOXLAB_IMPLEMENTATION"), "an oracle-test variable; the release has no tests"),
    (re.compile(r"make_assignments|assignments_up_to_date"), "the generator is not in the release"),
    (re.compile(r"\bdrift", re.IGNORECASE), "drift tests are instructors' business"),
    (re.compile(r"<!--\s*/?\s*(instructor|student)"), "a marker left in the student text"),
    (re.compile(r"mutant|MutantSuite|mutant_hints", re.IGNORECASE),
     "the mutant suite quotes the solution's bugs and calibrates the grader: instructors' business"),
    (re.compile(r"\bcalibrat", re.IGNORECASE), "calibrating the thresholds is instructors' business"),
    (re.compile(r"courses/|--assignment\b|run_autograder|VOXLAB_AUTOGRADER"),
     "running a course (assignment files, the autograders) is instructors' business"),
]

# What a release ships besides the SHIPPED Markdown folders (tools/
# make_student_release.sh), as paths in the release: a link elsewhere is broken there.
SHIPPED_PATHS = ("CMakeLists.txt", "README.md", "README_framework.md", "framework", "shaders", "assignments",
                 "datasets", "docs", "expected", "tests/golden/scenes", "tools/setup.sh", "tools/nrrd_to_dicom.py")
LINK = re.compile(r"\]\(([^)\s]+)\)")

# The Markdown tools/make_student_release.sh ships (README.md as
# README_framework.md); keep in step with its copy list.
SHIPPED = ("README.md", "assignments", "datasets", "docs", "framework", "shaders")

FENCE = re.compile(r"^\s*(```|~~~)")


class MarkupError(Exception):
    pass


def student_text(text, name="text"):
    """The student version of one Markdown file, or None when the whole file
    is left out. Raises MarkupError on unbalanced or misplaced markers."""
    lines = text.split("\n")
    if lines and lines[0].strip() == INSTRUCTOR_FILE:
        return None
    out = []
    block = None  # None, "instructor" or "student"
    opened = 0
    fence = None
    for k, line in enumerate(lines, 1):
        s = line.strip()
        marker = s in (INSTRUCTOR_BEGIN, INSTRUCTOR_END, STUDENT_BEGIN, INSTRUCTOR_FILE) or (
            block == "student" and s == STUDENT_END)
        if not marker:
            if fence:
                if re.match(r"^\s*" + re.escape(fence) + r"\s*$", line):
                    fence = None
            elif FENCE.match(line):
                fence = FENCE.match(line).group(1)
            if block != "instructor":
                out.append(line)
            continue
        if fence:
            raise MarkupError(f"{name}:{k}: marker inside a code block")
        if s == INSTRUCTOR_FILE:
            raise MarkupError(f"{name}:{k}: {INSTRUCTOR_FILE} belongs on the first line")
        if s in (INSTRUCTOR_BEGIN, STUDENT_BEGIN):
            if block:
                raise MarkupError(f"{name}:{k}: {s} inside the {block} block opened on line {opened}")
            block, opened = ("instructor" if s == INSTRUCTOR_BEGIN else "student"), k
            continue
        if s == INSTRUCTOR_END and block != "instructor":
            raise MarkupError(f"{name}:{k}: {INSTRUCTOR_END} without {INSTRUCTOR_BEGIN}")
        # The end of a block. A removed block leaves one blank line, not two.
        if block == "instructor" and out and not out[-1].strip() and k < len(lines) and not lines[k].strip():
            out.pop()
        block = None
    if block:
        raise MarkupError(f"{name}:{opened}: the {block} block is never closed")
    if fence:
        raise MarkupError(f"{name}: a code block is never closed")
    return "\n".join(out)


def problems_in(text, name):
    """Instructor material left in a student text, one line each."""
    found = []
    for k, line in enumerate(text.split("\n"), 1):
        for pattern, why in FORBIDDEN:
            m = pattern.search(line)
            if m:
                found.append(f"{name}:{k}: '{m.group(0)}' ({why}): {line.strip()[:100]}")
    return found


def link_targets(text):
    """(line, target) of each relative link of a Markdown text (no web
    addresses, no anchors within the page), the target without its anchor."""
    fence = False
    for k, line in enumerate(text.split("\n"), 1):
        if FENCE.match(line):
            fence = not fence
            continue
        if fence:
            continue
        for m in LINK.finditer(line):
            target = m.group(1).split("#")[0]
            if target and not re.match(r"^[a-z][a-z0-9+.-]*:", target):
                yield k, target


def broken_links(text, name, ships):
    """The links of `text` (the student text of release file `name`) whose
    target the release does not hold: `ships(path)` says whether it does."""
    found = []
    for k, target in link_targets(text):
        path = os.path.normpath(os.path.join(os.path.dirname(name), target))
        if path.startswith("..") or not ships(path):
            found.append(f"{name}:{k}: a link to '{target}', which the student release does not have")
    return found


def source_ships(root):
    """For a source tree: whether a release path names something a release
    of it ships (README_framework.md is its README.md; an instructor-only
    Markdown file is left out)."""
    def ships(path):
        if not any(path == p or path.startswith(p + os.sep) for p in SHIPPED_PATHS):
            return False
        if path.startswith("expected"):
            return True  # rendered by the release
        source = os.path.join(root, "README.md" if path == "README_framework.md" else path)
        if not os.path.exists(source):
            return False
        if source.endswith(".md") and os.path.isfile(source):
            with open(source, encoding="utf-8") as f:
                return f.readline().strip() != INSTRUCTOR_FILE
        return True
    return ships


def headings(text):
    out, fence = [], False
    for line in text.split("\n"):
        if FENCE.match(line):
            fence = not fence
        elif not fence and line.startswith("## "):
            out.append(line.strip())
    return out


def markdown_under(folder):
    """(path, name relative to `folder`) of every Markdown file under it."""
    for sub, _, names in os.walk(folder):
        for n in sorted(names):
            if n.endswith(".md"):
                path = os.path.join(sub, n)
                yield path, os.path.relpath(path, folder)


def shipped_markdown(root):
    """(path, name in the release) of every Markdown file a release ships."""
    for item in SHIPPED:
        path = os.path.join(root, item)
        if os.path.isfile(path):
            yield path, "README_framework.md" if item == "README.md" else item
            continue
        for full, name in markdown_under(path):
            yield full, os.path.join(item, name)


def student_versions(files, problems):
    """(path, name, text, student text) of each (path, name) in `files`; the
    student text is None for an instructor-only file. A file with a markup
    error adds it to `problems` and is left out."""
    for path, name in files:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        try:
            student = student_text(text, name)
        except MarkupError as e:
            problems.append(str(e))
            continue
        yield path, name, text, student


def check(root):
    """Problems with the student text of the Markdown a release of `root`
    ships: markup errors, instructor material left in, and handouts whose
    student text lost a section (the template: goals, what to implement,
    pitfalls, run it, check it, reading)."""
    problems, files, left_out = [], 0, 0
    for _, name, text, student in student_versions(shipped_markdown(root), problems):
        if student is None:
            left_out += 1
            continue
        files += 1
        problems += problems_in(student, name)
        problems += broken_links(student, name, source_ships(root))
        if re.match(r"assignments/\w+/README\.md$", name):
            lost = [h for h in headings(text) if h not in headings(student)]
            problems += [f"{name}: the student text loses the section '{h}'" for h in lost]
    return problems, files, left_out


def release(out):
    """Rewrites every Markdown file under a release folder to its student
    text (removing instructor-only files), then checks what is left."""
    problems, files, removed = [], 0, 0
    for path, name, text, student in student_versions(markdown_under(out), problems):
        if student is None:
            os.remove(path)
            removed += 1
            continue
        if student != text:
            with open(path, "w", encoding="utf-8") as f:
                f.write(student)
        files += 1
        problems += problems_in(student, name)
    # Links, once every file is its student text (instructor-only ones gone).
    for path, name in markdown_under(out):
        with open(path, encoding="utf-8") as f:
            problems += broken_links(f.read(), name, lambda p: os.path.exists(os.path.join(out, p)))
    return problems, files, removed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", nargs="?", const=ROOT, metavar="ROOT",
                      help="check the student text of the Markdown a release of ROOT ships")
    mode.add_argument("--print", metavar="FILE", help="print one file's student text")
    mode.add_argument("--release", metavar="OUT", help="rewrite a release's Markdown in place and check it")
    args = parser.parse_args()
    if args.print:
        try:
            with open(args.print, encoding="utf-8") as f:
                student = student_text(f.read(), args.print)
        except MarkupError as e:
            sys.exit(f"student_text: {e}")
        print("(left out of the student release)" if student is None else student, end="")
        return
    if args.check:
        problems, files, left_out = check(args.check)
        what = f"{files} Markdown files' student text, {left_out} left out of the release"
    else:
        problems, files, left_out = release(args.release)
        what = f"{files} Markdown files turned into their student text, {left_out} instructor-only removed"
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        sys.exit(f"student_text: instructor material in the student text ({len(problems)} problem(s)); "
                 f"mark it with {INSTRUCTOR_BEGIN} ... {INSTRUCTOR_END} (tools/student_text.py)")
    print(f"student_text: {what}: clean")


if __name__ == "__main__":
    main()
