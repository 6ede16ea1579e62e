#!/usr/bin/python3
"""Builds the bundled label maps from the bundled CTs by thresholding.

    /usr/bin/python3 tools/make_labels.py            # both
    /usr/bin/python3 tools/make_labels.py tooth      # datasets/tooth_labels.nrrd only

Each label map is uint8 on its CT's grid, with three labels and 0 for none:
    3  the hard part:  smoothed value >= HIGH
    2  the body:       smoothed value in [LOW, HIGH)
    1  the cavity:     smoothed value < LOW, not connected to the box's border through such
                       voxels (the air outside is, and stays 0)
tooth (datasets/tooth.nrrd, uint8): 1 pulp, 2 dentine, 3 enamel; LOW 118, HIGH 205, in the
    valleys of the histogram between air (peak near 78), dentine (162) and enamel (234).
headsq_hu (datasets/headsq_hu.nrrd, int16 Hounsfield-like, spacing 3.2 3.2 1.5): 1 enclosed
    air (sinuses, ventricles), 2 soft tissue, 3 bone; LOW -420, HIGH 520.

The smoothed value is the mean over each voxel's 3x3x3 neighbourhood (the CTs are noisy: a
threshold on raw values leaves speckles). Only connected pieces (6-neighbourhood) of at least
MIN_PIECE voxels are kept; the rest becomes label 0.

Standard library only (gzip, struct, collections), seconds each.
"""
import collections
import gzip
import sys

import struct

CAVITY, BODY, HARD = 1, 2, 3
RECIPES = {
    # name: (source, target, LOW, HIGH, minimum piece per label, label names)
    "tooth": ("datasets/tooth.nrrd", "datasets/tooth_labels.nrrd", 118, 205,
              {CAVITY: 50, BODY: 500, HARD: 500}, "1 pulp, 2 dentine, 3 enamel"),
    "headsq_hu": ("datasets/headsq_hu.nrrd", "datasets/headsq_hu_labels.nrrd", -420, 520,
                  {CAVITY: 20, BODY: 500, HARD: 200}, "1 enclosed air, 2 soft tissue, 3 bone"),
}


def read_nrrd(path):
    raw = open(path, "rb").read()
    end = raw.index(b"\n\n")
    header = dict(line.split(": ", 1) for line in raw[:end].decode().splitlines()[1:] if ": " in line)
    kind = header.get("type")
    if kind not in ("uchar", "short") or header.get("encoding") != "gzip" or header.get("endian", "little") != "little":
        sys.exit(f"{path}: expected a gzip NRRD of uchar or little-endian short")
    dims = tuple(int(x) for x in header["sizes"].split())
    data = gzip.decompress(raw[end + 2:])
    if kind == "short":
        data = struct.unpack(f"<{len(data) // 2}h", data)
    return dims, header.get("spacings", "1 1 1"), data


def box_mean(data, dims):
    """Mean over the 3x3x3 neighbourhood, clamped at the border, separably (x, then y, then z)."""
    nx, ny, nz = dims
    values = list(data)
    for axis, stride, n in ((0, 1, nx), (1, nx, ny), (2, nx * ny, nz)):
        out = [0.0] * len(values)
        for index in range(len(values)):
            i = (index // stride) % n
            lo = index - stride if i > 0 else index
            hi = index + stride if i < n - 1 else index
            out[index] = (values[lo] + values[index] + values[hi]) / 3.0
        values = out
    return values


def neighbours(index, dims):
    nx, ny, nz = dims
    i, j, k = index % nx, (index // nx) % ny, index // (nx * ny)
    if i > 0: yield index - 1
    if i < nx - 1: yield index + 1
    if j > 0: yield index - nx
    if j < ny - 1: yield index + nx
    if k > 0: yield index - nx * ny
    if k < nz - 1: yield index + nx * ny


def pieces(labels, dims, label):
    """The 6-connected pieces of one label, as lists of voxel indices."""
    seen = bytearray(len(labels))
    for start in range(len(labels)):
        if labels[start] != label or seen[start]:
            continue
        seen[start] = 1
        piece, queue = [], collections.deque([start])
        while queue:
            v = queue.popleft()
            piece.append(v)
            for w in neighbours(v, dims):
                if labels[w] == label and not seen[w]:
                    seen[w] = 1
                    queue.append(w)
        yield piece


def on_border(index, dims):
    nx, ny, nz = dims
    i, j, k = index % nx, (index // nx) % ny, index // (nx * ny)
    return i in (0, nx - 1) or j in (0, ny - 1) or k in (0, nz - 1)


def label(data, dims, low, high, min_piece):
    smooth = box_mean(data, dims)
    labels = bytearray(len(data))
    for index, v in enumerate(smooth):
        labels[index] = HARD if v >= high else BODY if v >= low else CAVITY
    # The low voxels connected to the border are the air outside, not a cavity.
    for piece in pieces(labels, dims, CAVITY):
        if any(on_border(v, dims) for v in piece):
            for v in piece:
                labels[v] = 0
    for name in (HARD, BODY, CAVITY):
        for piece in pieces(labels, dims, name):
            if len(piece) < min_piece[name]:
                for v in piece:
                    labels[v] = 0
    return labels


def write_nrrd(path, dims, spacings, labels, names):
    header = (f"NRRD0004\n# labels: 0 none, {names} (tools/make_labels.py)\n"
              f"type: uchar\ndimension: 3\nsizes: {dims[0]} {dims[1]} {dims[2]}\nspacings: {spacings}\n"
              "encoding: gzip\n\n")
    with open(path, "wb") as f:
        f.write(header.encode() + gzip.compress(bytes(labels), compresslevel=9, mtime=0))


def main():
    for name in sys.argv[1:] or list(RECIPES):
        if name not in RECIPES:
            sys.exit(f"make_labels.py: unknown label map '{name}' (known: {', '.join(RECIPES)})")
        source, target, low, high, min_piece, names = RECIPES[name]
        dims, spacings, data = read_nrrd(source)
        labels = label(data, dims, low, high, min_piece)
        write_nrrd(target, dims, spacings, labels, names)
        counts = collections.Counter(labels)
        print(target, dims, {l: counts[l] for l in (0, CAVITY, BODY, HARD)})


if __name__ == "__main__":
    main()
