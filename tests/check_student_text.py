#!/usr/bin/env python3
"""Checks tools/student_text.py, which turns voxlab's Markdown into what the
student release ships, and the Markdown itself:

  1. every Markdown file a release ships (the handouts in assignments/, the
     READMEs, docs/) has balanced markers, and its student text holds no
     instructor material (build/tests, VOXLAB_STAGE_ROOT, the generator,
     drift tests, ...) and keeps every section of its handout;
  2. the rules on small texts: instructor blocks removed, student blocks
     shown, instructor-only files left out, bad markers refused by line;
  3. --release on a small folder rewrites it and fails on what is left:
     instructor material (the mutant suite, a course's files too) and links
     to files the release does not have (reference/, instructor-only pages).

Usage: check_student_text.py PROJECT_SOURCE_DIR
Exit: 0 passed, 1 failed.
"""
import os
import subprocess
import sys
import tempfile


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[-2])
    src = os.path.abspath(sys.argv[1])
    tool = os.path.join(src, "tools", "student_text.py")
    sys.path.insert(0, os.path.dirname(tool))
    import student_text as st  # noqa: E402

    failures = []

    def expect(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    # 1. The repository's Markdown.
    r = subprocess.run([sys.executable, tool, "--check", src], capture_output=True, text=True)
    expect(r.returncode == 0, "the Markdown a release ships has clean student text" +
           ("" if r.returncode == 0 else ":\n" + r.stderr.strip()))
    problems, files, left_out = st.check(src)
    handouts = [n for _, n in st.shipped_markdown(src) if n.startswith("assignments/") and n.count("/") == 2]
    expect(len(handouts) >= 10 and files > len(handouts), f"{files} files checked, {len(handouts)} of them handouts")
    mip = open(os.path.join(src, "assignments", "mip", "README.md"), encoding="utf-8").read()
    student = st.student_text(mip)
    expect("build/tests" in mip and "build/tests" not in student and "voxlab check --stage mip" in student,
           "the MIP handout keeps its oracle tests for instructors and its self-check for students")

    # 2. The rules.
    text = "\n".join([
        "# Title", "", "For everyone.", "",
        st.INSTRUCTOR_BEGIN, "Run build/tests/test_x.", "", "```sh", "ctest -R x", "```",
        st.INSTRUCTOR_END, "",
        st.STUDENT_BEGIN, "Rebuild with `cmake --build build`.", "```sh", "cmake --build build", "```",
        st.STUDENT_END, "", "## Next", ""])
    out = st.student_text(text)
    expect(out == "\n".join(["# Title", "", "For everyone.", "", "Rebuild with `cmake --build build`.",
                             "```sh", "cmake --build build", "```", "", "## Next", ""]),
           "instructor blocks are removed (one blank line left), student blocks shown")
    expect(st.student_text(st.INSTRUCTOR_FILE + "\n# Notes\n") is None, "an instructor-only file is left out")
    expect(st.student_text("no markers\n") == "no markers\n", "text without markers is unchanged")
    bad = {
        "unclosed block": "a\n" + st.INSTRUCTOR_BEGIN + "\nb\n",
        "end without begin": "a\n" + st.INSTRUCTOR_END + "\n",
        "nested blocks": st.INSTRUCTOR_BEGIN + "\n" + st.STUDENT_BEGIN + "\n-->\n" + st.INSTRUCTOR_END + "\n",
        "marker in a code block": "```\n" + st.INSTRUCTOR_BEGIN + "\n```\n" + st.INSTRUCTOR_END + "\n",
        "block ending in a code block": st.STUDENT_BEGIN + "\n```\n-->\n```\n",
        "file marker not first": "# T\n" + st.INSTRUCTOR_FILE + "\n",
    }
    for what, t in bad.items():
        try:
            st.student_text(t, "x.md")
            expect(False, f"{what} is refused")
        except st.MarkupError as e:
            expect(str(e).startswith("x.md:"), f"{what} is refused ({e})")

    # 3. --release on a folder.
    with tempfile.TemporaryDirectory(prefix="voxlab_student_text_") as tmp:
        files = {
            "README.md": text,
            "docs/notes.md": st.INSTRUCTOR_FILE + "\nbuild/tests everywhere\n",
            "docs/ok.md": "nothing to hide\n",
        }
        for rel, t in files.items():
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w", encoding="utf-8") as f:
                f.write(t)
        r = subprocess.run([sys.executable, tool, "--release", tmp], capture_output=True, text=True)
        readme = open(os.path.join(tmp, "README.md"), encoding="utf-8").read()
        expect(r.returncode == 0 and readme == out and not os.path.exists(os.path.join(tmp, "docs", "notes.md")),
               f"--release rewrites a folder and removes instructor-only files ({r.stdout.strip()})")
        with open(os.path.join(tmp, "docs", "ok.md"), "a", encoding="utf-8") as f:
            f.write("Rebuild with cmake -DVOXLAB_STAGE_ROOT=assignments; see the drift test.\n")
        r = subprocess.run([sys.executable, tool, "--release", tmp], capture_output=True, text=True)
        expect(r.returncode != 0 and "docs/ok.md:2: 'VOXLAB_STAGE_ROOT'" in r.stderr and "'drift'" in r.stderr,
               "--release fails on instructor material left in, naming file, line and term")
        # The mutant suite, calibration and running a course are instructors' business too.
        with open(os.path.join(tmp, "docs", "ok.md"), "w", encoding="utf-8") as f:
            f.write("nothing to hide\nThe mutant suite calibrates it.\nGrade with --assignment courses/a.json.\n")
        r = subprocess.run([sys.executable, tool, "--release", tmp], capture_output=True, text=True)
        expect(r.returncode != 0 and "docs/ok.md:2: 'mutant'" in r.stderr and "docs/ok.md:3: '--assignment'" in r.stderr,
               "--release fails on the mutant suite and a course's files")
        # A link to what the release does not hold (reference/, a page left out) is broken there.
        with open(os.path.join(tmp, "docs", "ok.md"), "w", encoding="utf-8") as f:
            f.write("See [the handout](../reference/mip/README.md), [notes](notes.md) and [this](ok.md#x).\n")
        r = subprocess.run([sys.executable, tool, "--release", tmp], capture_output=True, text=True)
        expect(r.returncode != 0 and "'../reference/mip/README.md'" in r.stderr and "'notes.md'" in r.stderr
               and "'ok.md'" not in r.stderr,
               "--release fails on links to reference/ and to an instructor-only page, not on one that ships")
    # The same for the source tree: a shipped page linking reference/ fails --check.
    problems = st.broken_links("[h](../reference/cubic/README.md) [g](grading.md) [c](courses.md)",
                               "docs/x.md", st.source_ships(src))
    expect(len(problems) == 2 and "reference/cubic" in problems[0] and "courses.md" in problems[1],
           f"--check finds links to reference/ and instructor-only docs/courses.md ({problems})")

    print(f"{len(failures)} failure(s)" if failures else "student text: all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
