#!/usr/bin/python3
"""Writes a large test volume for the out-of-core figures in docs/performance.md.

bonsai (256^3 uint8) with every voxel repeated along each axis, as NRRD:

    /usr/bin/python3 bench/make_large_volume.py OUT.nrrd --repeat 4 4 4          # 1024^3, 1 GiB
    /usr/bin/python3 bench/make_large_volume.py OUT.nrrd --repeat 8 8 2 --gzip   # 2048x2048x512

Written slice by slice, so it needs little memory itself. Needs numpy
(Debian: python3-numpy).
"""
import argparse
import gzip
import os
import sys

import numpy as np


def read_nrrd_uint8(path):
    with open(path, "rb") as f:
        data = f.read()
    header, _, payload = data.partition(b"\n\n")
    fields = {}
    for line in header.decode("latin-1").splitlines()[1:]:
        if ":" in line and not line.startswith("#"):
            key, value = line.split(":", 1)
            fields[key.strip()] = value.strip()
    if fields.get("type") not in ("uchar", "uint8", "unsigned char"):
        sys.exit(f"{path}: expected uint8 voxels, not {fields.get('type')}")
    if fields.get("encoding") in ("gzip", "gz"):
        payload = gzip.decompress(payload)
    nx, ny, nz = (int(v) for v in fields["sizes"].split())
    return np.frombuffer(payload, dtype=np.uint8).reshape(nz, ny, nx)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    parser.add_argument("--source", default=os.path.join(here, "..", "datasets", "bonsai.nrrd"))
    parser.add_argument("--repeat", type=int, nargs=3, default=[4, 4, 4], metavar=("RX", "RY", "RZ"))
    parser.add_argument("--gzip", action="store_true", help="gzip encoding (level 1) instead of raw")
    args = parser.parse_args()
    rx, ry, rz = args.repeat
    if min(args.repeat) < 1:
        sys.exit("--repeat: each factor must be at least 1")
    source = read_nrrd_uint8(args.source)
    nz, ny, nx = source.shape
    header = (f"NRRD0004\n# {os.path.basename(args.source)} with every voxel repeated {rx}x{ry}x{rz} "
              f"(bench/make_large_volume.py)\ntype: uchar\ndimension: 3\nsizes: {nx * rx} {ny * ry} {nz * rz}\n"
              f"spacings: 1 1 1\nencoding: {'gzip' if args.gzip else 'raw'}\n\n")
    with open(args.out, "wb") as f:
        f.write(header.encode("ascii"))
        sink = gzip.GzipFile(fileobj=f, mode="wb", compresslevel=1) if args.gzip else f
        for z in range(nz):
            plane = np.repeat(np.repeat(source[z], ry, axis=0), rx, axis=1)
            block = plane.tobytes()
            for _ in range(rz):
                sink.write(block)
        if args.gzip:
            sink.close()
    print(f"{args.out}: {nx * rx}x{ny * ry}x{nz * rz} uint8")


if __name__ == "__main__":
    main()
