#!/usr/bin/python3
"""Every path of the repository that its text names exists.

Handouts, docs and comments point students and instructors at files
("framework/stages/marching_cubes/mesh.cpp, read it"); a file that moves
leaves such a pointer stale. This reads every tracked text file for paths
under framework/, shaders/, tools/, docs/, bench/ and web/ with a file
extension, and fails naming each one that does not exist, with where it is
named. Placeholders are not paths: a part in capitals (STAGE, NAME.h), in
angle brackets or with a wildcard. EXEMPT lists the files whose paths are
deliberately not this tree's (test fixtures, installed layouts).

usage: check_paths.py PROJECT_DIR
"""
import os
import re
import subprocess
import sys

PATH = re.compile(r"(?<![\w/$.<>-])((?:framework|shaders|tools|docs|bench|web)/[A-Za-z0-9_./<>*-]+?"
                  r"\.(?:cpp|h|glsl|frag|vert|py|sh|md|cmake|c)(?:\.in)?)(?![\w.])")

# Files whose paths name something else on purpose.
EXEMPT = {
    "tests/check_student_text.py": "fixtures: made-up files of a student's tree",
    "tests/check_paths.py": "its own examples",
}

BINARY = (".png", ".jpg", ".nrrd", ".raw", ".gz", ".zip", ".ttf", ".dcm", ".vol", ".dat", ".pgm", ".bin")


def placeholder(path):
    for part in path.split("/"):
        stem = part.split(".")[0]
        if (stem.isupper() and len(stem) > 1) or "<" in part or "*" in part:
            return True
    return False


def main():
    root = sys.argv[1]
    files = subprocess.run(["git", "-C", root, "ls-files"], capture_output=True, text=True, check=True).stdout.split()
    missing, named = {}, 0
    for f in files:
        if f in EXEMPT or f.startswith("datasets/") or f.lower().endswith(BINARY):
            continue
        try:
            with open(os.path.join(root, f), encoding="utf-8") as handle:
                lines = handle.read().split("\n")
        except (UnicodeDecodeError, IsADirectoryError, FileNotFoundError):
            continue
        for number, line in enumerate(lines, 1):
            for m in PATH.finditer(line):
                path = m.group(1)
                if placeholder(path):
                    continue
                named += 1
                if not os.path.exists(os.path.join(root, path)):
                    missing.setdefault(path, []).append(f"{f}:{number}")
    for path, where in sorted(missing.items()):
        print(f"{path}: named by {', '.join(where)}, but there is no such file")
    print(f"check_paths: {named} paths named, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
