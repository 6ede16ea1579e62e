#!/usr/bin/env bash
# The benchmarks through EGL, for a machine with a real GPU.
#
#   bench/gpu_bench.sh [VOXLAB] [FRAMES]
#
# Prints the OpenGL renderer string, then, on bonsai (orbit view azimuth 35,
# elevation 25, perspective, step 0.5, the dataset's transfer function), the
# median ms/frame of `voxlab bench --gl egl` (by the wall clock and by the
# GL's timestamps, which on a GPU are the GPU's own time) and the samples a
# second by the README's sampling rule, for the slow paths of
# docs/performance.md (composite, shaded composite, isosurface, MIP with the
# shader's trilinear and with the GPU's, the 2D transfer function) at
# 512x512 and 2048x2048, and one composite run on each bundled dataset at
# 1024x1024. EGL must find the GPU's driver (libEGL from glvnd and the
# vendor's EGL library); with none, the first bench says so and the script
# stops. The same scenes run on llvmpipe with VOXLAB_GL=osmesa and
# --gl osmesa in place of egl (set GL=osmesa).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
voxlab="${1:-$root/build/bin/voxlab}"
frames="${2:-20}"
gl="${GL:-egl}"
view=(--azimuth 35 --elevation 25 --projection perspective --step 0.5)

bench() {  # label, then bench arguments: prints one table row
  local label="$1"; shift
  local out
  out=$("$voxlab" bench "$@" "${view[@]}" --gl "$gl" --frames "$frames" --json) || {
    echo "gpu_bench.sh: $label: voxlab bench failed" >&2; exit 1; }
  python3 -c '
import json, sys
j = json.loads(sys.argv[2])
ms, gpu = j["median_ms"], j.get("gpu_median_ms")
rate = j.get("samples_per_second")
print("| %s | %.2f | %s | %.0f | %s |" % (sys.argv[1], ms, "%.2f" % gpu if gpu is not None else "n/a",
      1000.0 / ms, "%.3g" % rate if rate else "n/a"))' \
    "$label" "$out"
}
header() {
  echo "| $1 | ms/frame, wall (median) | ms/frame, GL timestamps (median) | frames/s | samples/s by the sampling rule |"
  echo "|---|---|---|---|---|"
}

"$voxlab" bench --dataset bonsai.nrrd --renderer mip --size 64x64 --frames 1 --gl "$gl" | grep '^gl:'
for size in 512 2048; do
  s=(--dataset bonsai.nrrd --size "${size}x${size}")
  echo
  echo "bonsai, ${size}x${size}, $frames frames"
  echo
  header "set-up"
  bench "composite" "${s[@]}" --renderer composite --tf tf/bonsai.json
  bench "composite, shaded" "${s[@]}" --renderer composite --tf tf/bonsai.json --param shading=1
  bench "iso (value 60)" "${s[@]}" --renderer iso --param isovalue=60
  bench "MIP, shader trilinear" "${s[@]}" --renderer mip --interpolation trilinear
  bench "MIP, GPU trilinear" "${s[@]}" --renderer mip --interpolation hardware
  bench "tf2d" "${s[@]}" --renderer tf2d --tf2d tf2d/bonsai.json
done
echo
echo "composite, every bundled dataset with a preset, 1024x1024, $frames frames"
echo
header "dataset"
for d in bonsai bucky cthead fuel headsq neghip stent tooth; do
  bench "$d" --dataset "$d.nrrd" --size 1024x1024 --renderer composite --tf "tf/$d.json"
done
