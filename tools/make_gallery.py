#!/usr/bin/env python3
"""Regenerates docs/gallery.md and docs/gallery/*.png.

The gallery shows the scenes of tests/golden/golden.json (one per renderer
and option, on real datasets) at 256 x 256, rendered headless with
build/bin/voxlab. Run it after a change that alters what the renderers draw:

    python3 tools/make_gallery.py [--size 256] [--voxlab build/bin/voxlab]
"""
import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COLUMNS = 3


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=256, help="image width and height in pixels")
    parser.add_argument("--voxlab", default=os.path.join(ROOT, "build", "bin", "voxlab"))
    args = parser.parse_args()
    if not os.access(args.voxlab, os.X_OK):
        sys.exit(f"make_gallery: {args.voxlab} not found: build first (tools/setup.sh --test)")

    golden = os.path.join(ROOT, "tests", "golden")
    with open(os.path.join(golden, "golden.json")) as f:
        entries = json.load(f)["images"]
    out_dir = os.path.join(ROOT, "docs", "gallery")
    os.makedirs(out_dir, exist_ok=True)
    env = dict(os.environ, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "2"), VOXLAB_GL="osmesa")

    cells = []
    for e in entries:
        name = e["name"]
        scene = os.path.join("tests", "golden", "scenes", name + ".json")
        size = f"{args.size}x{args.size}"
        start = time.time()
        result = subprocess.run([args.voxlab, "render", os.path.join(ROOT, scene), "--size", size,
                                 "--out", os.path.join(out_dir, name + ".png")],
                                env=env, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"make_gallery: {name}: {result.stderr.strip()}")
        print(f"{name}: {time.time() - start:.1f} s", flush=True)
        cells.append((e, f"voxlab render {scene} --size {size}"))

    lines = [
        "# Gallery",
        "",
        "One image per renderer and option, on the bundled datasets, rendered headless on Mesa llvmpipe.",
        "Each is a scene in `tests/golden/scenes/` (the golden-image test renders the same scenes at",
        "128 x 128); the command under each image reproduces it. Regenerate this page with",
        "`python3 tools/make_gallery.py`.",
        "",
    ]
    for row in range(0, len(cells), COLUMNS):
        chunk = cells[row:row + COLUMNS]
        lines.append("| " + " | ".join(f"**{e['title']}**" for e, _ in chunk) + " |")
        lines.append("|" + "---|" * len(chunk))
        lines.append("| " + " | ".join(f"![{e['name']}](gallery/{e['name']}.png)" for e, _ in chunk) + " |")
        lines.append("| " + " | ".join(f"{e['caption']}<br>`{cmd}`" for e, cmd in chunk) + " |")
        lines.append("")
    with open(os.path.join(ROOT, "docs", "gallery.md"), "w") as f:
        f.write("\n".join(lines))
    print("wrote docs/gallery.md")


if __name__ == "__main__":
    main()
