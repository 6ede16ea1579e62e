#!/usr/bin/python3
"""Splatting, shear-warp and marching cubes held against ray casting on the same data.

    /usr/bin/python3 bench/compare_object_order.py [--size 384] [--frames 5] [--out docs/images/object_order]

For each dataset (bonsai, tooth) and one orthographic oblique view it renders, with
build/bin/voxlab:
  composite at step 1 (one sample per voxel along a ray: the reference the others match),
  splat (sigma 0.7 voxel: one footprint per voxel), shearwarp (one slice per voxel),
  texslice3d at step 1, and iso and mesh at one isovalue (depth images too),
saves the images and the differences (|a - b| x 4) under --out, and prints a Markdown table of
mean SSIM, PSNR and mean difference against the reference (voxlab compare) and the median time
per frame (voxlab bench, the camera turning 0.5 degree a frame, so caches that depend on the view
are exercised). docs/object_order.md holds its output.
"""
import argparse
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VOXLAB = os.path.join(ROOT, "build", "bin", "voxlab")
DATASETS = {"bonsai": 60, "tooth": 180}  # isovalue for iso and mesh
VIEW = ["--azimuth", "30", "--elevation", "20", "--projection", "orthographic", "--zoom", "1.2"]


def run(args):
    env = dict(os.environ, LP_NUM_THREADS=os.environ.get("LP_NUM_THREADS", "2"), VOXLAB_GL="osmesa")
    r = subprocess.run([VOXLAB] + args, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"compare_object_order: voxlab {' '.join(args)}: {r.stderr.strip()}")
    return r.stdout


def techniques(name, isovalue):
    tf = ["--tf", f"tf/{name}.json"]
    return [
        ("composite step 1", ["--renderer", "composite", "--step", "1"] + tf, "ref"),
        ("splat sigma 0.7", ["--renderer", "splat", "--param", "radius=0.7"] + tf, "ref"),
        ("shearwarp", ["--renderer", "shearwarp"] + tf, "ref"),
        ("texslice3d step 1", ["--renderer", "texslice3d", "--step", "1"] + tf, "ref"),
        (f"iso {isovalue}", ["--renderer", "iso", "--param", f"isovalue={isovalue}"], "iso"),
        (f"mesh {isovalue}", ["--renderer", "mesh", "--param", f"isovalue={isovalue}"], "iso"),
        (f"iso {isovalue}, depth", ["--renderer", "iso", "--param", f"isovalue={isovalue}", "--param", "depth=1"], "isodepth"),
        (f"mesh {isovalue}, depth", ["--renderer", "mesh", "--param", f"isovalue={isovalue}", "--param", "depth=1"], "isodepth"),
    ]


def metrics(a, b):
    text = run(["compare", a, b])
    grab = lambda pattern: re.search(pattern, text).group(1)
    psnr = grab(r"PSNR:\s+(\S+)")
    return {"ssim": grab(r"SSIM:\s+([\d.]+)"), "psnr": psnr, "mean": grab(r"mean difference:\s+([\d.]+)")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=384)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "images", "object_order"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    size = ["--size", f"{args.size}x{args.size}"]
    print("| dataset | technique | against | mean SSIM | PSNR (dB) | mean difference (grey levels) | ms/frame |")
    print("|---|---|---|---|---|---|---|")
    for name, isovalue in DATASETS.items():
        refs = {}
        for label, options, group in techniques(name, isovalue):
            slug = re.sub(r"[^a-z0-9]+", "_", label.lower()).strip("_")
            png = os.path.join(args.out, f"{name}_{slug}.png")
            run(["render", "--dataset", f"{name}.nrrd", "--out", png] + VIEW + size + options)
            bench = run(["bench", "--dataset", f"{name}.nrrd", "--frames", str(args.frames)] + VIEW + size + options)
            ms = re.search(r"median ([\d.]+)", bench).group(1)
            if group not in refs:
                refs[group] = (label, png)
                print(f"| {name} | {label} | (reference) | | | | {ms} |")
                continue
            m = metrics(refs[group][1], png)
            diff = os.path.join(args.out, f"{name}_{slug}_diff.png")
            run(["compare", refs[group][1], png, "--diff", diff])
            print(f"| {name} | {label} | {refs[group][0]} | {m['ssim']} | {m['psnr']} | {m['mean']} | {ms} |", flush=True)


if __name__ == "__main__":
    main()
