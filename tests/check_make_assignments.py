#!/usr/bin/env python3
"""Checks tools/make_assignments.py on a temporary copy of two stages of
reference/ to which binary files were added (a PNG beside the scenes, a NRRD
volume and a raw file with every byte value), as an instructor may leave
them: the tool must copy them byte for byte, keep its other rules (stubs,
no mutants.json, no hidden scenes), report them in --check, and refuse a
file it has to rewrite that is not UTF-8 text with a one-line error.

Usage: check_make_assignments.py PROJECT_SOURCE_DIR
Exit: 0 passed, 1 failed.
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

STAGES = ("mip", "texslice2d")  # a GLSL stage with a hidden scene, a C++ stage


def png(width, height):
    """A small valid grey PNG: its signature byte 0x89 is not UTF-8."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\0" + bytes((x * 37 + y * 11) % 256 for x in range(width)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def nrrd():
    """A NRRD with an attached raw payload holding bytes >= 0x80 and line ends."""
    header = (b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n"
              b"space directions: (1,0,0) (0,1,0) (0,0,1)\n\n")
    payload = bytes((i * 53 + 200) % 256 for i in range(61)) + b"\r\n\r"
    return header + payload


BINARY_FILES = {
    "mip/scenes/preview.png": png(5, 3),
    "mip/tiny.nrrd": nrrd(),
    "texslice2d/scenes/data.raw": bytes(range(256)),
    "texslice2d/notes.txt": b"copied as it is,\r\nline ends included\r\n",
}


def run(tool, *args):
    return subprocess.run([sys.executable, tool, *args], capture_output=True, text=True)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[-2])
    src = os.path.abspath(sys.argv[1])
    failures = []

    def expect(ok, what):
        print(("ok    " if ok else "FAIL  ") + what)
        if not ok:
            failures.append(what)

    with tempfile.TemporaryDirectory(prefix="voxlab_make_assignments_") as tmp:
        os.makedirs(os.path.join(tmp, "tools"))
        for name in ("make_assignments.py", "manifest_format.py"):
            shutil.copy(os.path.join(src, "tools", name), os.path.join(tmp, "tools"))
        for stage in STAGES:
            shutil.copytree(os.path.join(src, "reference", stage), os.path.join(tmp, "reference", stage))
        for rel, data in BINARY_FILES.items():
            with open(os.path.join(tmp, "reference", rel), "wb") as f:
                f.write(data)
        tool = os.path.join(tmp, "tools", "make_assignments.py")
        assignments = os.path.join(tmp, "assignments")

        r = run(tool)
        expect(r.returncode == 0, f"make_assignments.py runs with binary files beside the scenes (exit {r.returncode})")
        if r.returncode != 0:
            print((r.stderr or r.stdout).strip()[-2000:])
            return 1

        for rel, data in BINARY_FILES.items():
            path = os.path.join(assignments, rel)
            same = os.path.isfile(path) and open(path, "rb").read() == data
            expect(same, f"assignments/{rel} is reference/{rel} byte for byte")

        # Its other rules still hold.
        mip = open(os.path.join(assignments, "mip", "mip.glsl"), encoding="utf-8").read()
        expect("not_implemented();" in mip and "BEGIN SOLUTION" not in mip, "mip.glsl is a stub")
        cpp = open(os.path.join(assignments, "texslice2d", "slice_axis.cpp"), encoding="utf-8").read()
        expect('throw NotImplemented("chooseSliceAxis");' in cpp and "BEGIN SOLUTION" not in cpp,
               "slice_axis.cpp is a stub")
        expect(not any(os.path.exists(os.path.join(assignments, s, "mutants.json")) for s in STAGES),
               "no mutants.json copied")
        manifest = open(os.path.join(assignments, "mip", "grading.json"), encoding="utf-8").read()
        expect("ct_signed_air" not in manifest and
               not os.path.exists(os.path.join(assignments, "mip", "scenes", "ct_signed_air.json")),
               "the hidden scene is neither in the manifest nor copied")

        r = run(tool, "--check")
        expect(r.returncode == 0, f"--check passes on what it wrote (exit {r.returncode}: {r.stderr.strip()})")

        # --check compares binary files too.
        preview = os.path.join(assignments, "mip", "scenes", "preview.png")
        with open(preview, "r+b") as f:
            f.seek(20)
            byte = f.read(1)
            f.seek(20)
            f.write(bytes([byte[0] ^ 0xFF]))
        r = run(tool, "--check")
        expect(r.returncode == 1 and "assignments/mip/scenes/preview.png: differs" in r.stderr,
               "--check reports a changed binary file")
        os.remove(os.path.join(assignments, "texslice2d", "scenes", "data.raw"))
        r = run(tool, "--check")
        expect(r.returncode == 1 and "assignments/texslice2d/scenes/data.raw: missing" in r.stderr,
               "--check reports a missing binary file")
        r = run(tool)
        r2 = run(tool, "--check")
        expect(r.returncode == 0 and r2.returncode == 0 and open(preview, "rb").read() == BINARY_FILES["mip/scenes/preview.png"],
               "a second run restores them")

        # A file the tool rewrites must be text: a clear error, not a traceback.
        with open(os.path.join(tmp, "reference", "mip", "broken.glsl"), "wb") as f:
            f.write(b"float f() {\n  return 1.0; // \xff\xfe\n}\n")
        r = run(tool)
        expect(r.returncode != 0 and "reference/mip/broken.glsl: not UTF-8 text" in r.stderr and
               "Traceback" not in r.stderr, f"a .glsl that is not UTF-8 is refused by name ({r.stderr.strip()})")

    print(f"{len(failures)} failure(s)" if failures else "make_assignments.py handles binary files")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
