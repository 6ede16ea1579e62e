#!/usr/bin/python3
"""Measures the tables of docs/performance.md and prints them as Markdown.

    LP_NUM_THREADS=2 /usr/bin/python3 bench/performance_table.py [--frames N] [--size 512] [--quick]

Table 1, per bundled dataset (composite and MIP; the 2D transfer function
on the datasets with a preset; the isosurface at value 60 on two): `voxlab
bench` with empty-space skipping off and on (median ms/frame, speed-up, samples skipped) and how
far the two images differ (`voxlab compare`: largest difference in grey
levels, PSNR).

Table 2, on bonsai with compositing: the optimisations one at a time, each
image compared with the plain one (no skipping, no early termination,
the shader's trilinear sampling).

Every scene: 512 x 512 (--size), step 0.5, orbit view azimuth 35 and
elevation 25, perspective, the dataset's transfer-function preset for
compositing. --quick runs three datasets instead of all (for a smoke test).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRESETS = ["bonsai", "bucky", "cthead", "fuel", "headsq", "neghip", "stent", "tooth"]


def run(cmd):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"performance_table.py: {' '.join(cmd)} failed:\n{done.stderr}")
    return done.stdout


def bench(voxlab, scene, frames):
    return json.loads(run([voxlab, "bench", *scene, "--frames", str(frames), "--warmup", "1", "--json"]))


def difference(voxlab, a_scene, b_scene, folder):
    a, b = os.path.join(folder, "a.png"), os.path.join(folder, "b.png")
    run([voxlab, "render", *a_scene, "--out", a])
    run([voxlab, "render", *b_scene, "--out", b])
    text = run([voxlab, "compare", a, b])
    largest = float(re.search(r"max difference:\s+([\d.]+)", text).group(1))
    psnr = re.search(r"PSNR:\s+(\S+)", text).group(1)
    return largest, psnr


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--voxlab", default=os.path.join(ROOT, "build", "bin", "voxlab"))
    args = ap.parse_args()
    view = ["--size", f"{args.size}x{args.size}", "--step", "0.5", "--azimuth", "35", "--elevation", "25",
            "--projection", "perspective"]
    folder = tempfile.mkdtemp(prefix="voxlab_perf_")
    datasets = PRESETS[:3] if args.quick else PRESETS

    print("| dataset | renderer | skipping off (ms) | skipping on (ms) | speed-up | samples skipped | "
          "image: largest difference | PSNR |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    rows = [(name, renderer) for name in datasets for renderer in ["composite", "mip"]]
    # The other renderers that skip: the 2D transfer function (its presets) and the isosurface.
    rows += [(name, "tf2d") for name in ["bonsai", "cthead", "tooth"][: 1 if args.quick else 3]]
    rows += [(name, "iso") for name in ["bonsai", "cthead"][: 1 if args.quick else 2]]
    for name, renderer in rows:
        scene = ["--dataset", f"{name}.nrrd", "--renderer", renderer, *view]
        if renderer == "composite":
            scene += ["--tf", f"tf/{name}.json"]
        elif renderer == "tf2d":
            scene += ["--tf2d", f"tf2d/{name}.json"]
        elif renderer == "iso":
            scene += ["--param", "isovalue=60"]
        off = bench(args.voxlab, scene + ["--skip-empty-space", "off"], args.frames)
        on = bench(args.voxlab, scene, args.frames)
        largest, psnr = difference(args.voxlab, scene + ["--skip-empty-space", "off"], scene, folder)
        print(f"| {name} | {renderer} | {off['median_ms']:.0f} | {on['median_ms']:.0f} | "
              f"{off['median_ms'] / on['median_ms']:.1f}x | {100 * on['skipped_fraction']:.0f}% | "
              f"{largest:g} | {psnr} |", flush=True)

    print()
    scene = ["--dataset", "bonsai.nrrd", "--renderer", "composite", "--tf", "tf/bonsai.json", *view]
    plain = scene + ["--skip-empty-space", "off", "--param", "early_termination=1"]
    steps = [
        ("plain: every sample, shader trilinear", plain),
        ("+ early ray termination (opacity 0.99)", scene + ["--skip-empty-space", "off"]),
        ("+ empty-space skipping", scene),
        ("+ GPU trilinear filtering instead of the shader's", scene + ["--interpolation", "hardware"]),
    ]
    print("| bonsai, composite | ms/frame | samples skipped | image vs plain: largest difference | PSNR |")
    print("|---|---:|---:|---:|---:|")
    for label, options in steps:
        figures = bench(args.voxlab, options, args.frames)
        largest, psnr = difference(args.voxlab, plain, options, folder)
        print(f"| {label} | {figures['median_ms']:.0f} | {100 * figures['skipped_fraction']:.0f}% | {largest:g} | "
              f"{psnr} |", flush=True)
    print(f"\ngl: {figures['gl']}")


if __name__ == "__main__":
    main()
