#!/usr/bin/env bash
# A volume larger than this machine's memory, drawn from disk (issue 36).
#
#   bench/stream_large_volume.sh [SIDE] [FOLDER]
#
# Makes FOLDER/huge.raw (default /tmp/voxlab-huge), SIDE^3 uint8 voxels
# (default: the smallest SIDE whose volume is 1.25 times the machine's
# memory), as a sparse file: zero but for a few boxes of known values, so it
# takes little disk. Its NRRD header (huge.nhdr) names it as detached raw
# data. Then `voxlab bench` draws a nearest MIP along +z at 512x512, two
# frames, with a 1 GiB volume cap (so the volume is streamed from the file)
# and the default GPU-memory budget, under /usr/bin/time; prints the volume's
# size, the peak resident memory, the load time and the time a frame.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
voxlab="${VOXLAB:-$root/build/bin/voxlab}"
mem_kib=$(awk '/^MemTotal:/ {print $2}' /proc/meminfo)
side="${1:-$(python3 -c 'import sys; m = int(sys.argv[1]) * 1024 * 1.25; print(int(m ** (1 / 3)) + 1)' "$mem_kib")}"
dir="${2:-/tmp/voxlab-huge}"
mkdir -p "$dir"
python3 - "$dir/huge.raw" "$side" <<'PY'
import sys
path, side = sys.argv[1], int(sys.argv[2])
with open(path, "wb") as f:
    f.truncate(side ** 3)
    for b, (fx, fy, fz) in enumerate([(0.1, 0.2, 0.1), (0.5, 0.5, 0.5), (0.8, 0.3, 0.9)]):
        s = max(8, side // 20)
        x0, y0, z0 = int(fx * side), int(fy * side), int(fz * side)
        row = bytes((x * 7 + b * 61) % 251 + 1 for x in range(s))
        for z in range(z0, z0 + s):
            for y in range(y0, y0 + s):
                f.seek((z * side + y) * side + x0)
                f.write(row)
PY
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: %d %d %d\nencoding: raw\ndata file: huge.raw\n' \
  "$side" "$side" "$side" > "$dir/huge.nhdr"
echo "volume: ${side}^3 uint8, $((side * side * side / 1048576)) MiB, machine memory $((mem_kib / 1024)) MiB," \
     "on disk $(du -m "$dir/huge.raw" | cut -f1) MiB (sparse)"
/usr/bin/time -f 'peak resident memory: %M kB, wall %e s' "$voxlab" bench --dataset "$dir/huge.nhdr" \
  --renderer mip --view +z --interpolation nearest --size 512x512 --frames 2 --warmup 0 --max-volume-mib 1024 2>&1 |
  grep -E 'ms/frame|peak|load|upload|brick|skipped' || true
