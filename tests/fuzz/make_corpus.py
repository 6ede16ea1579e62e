#!/usr/bin/env python3
"""Seed corpora for voxlab's fuzz targets (tests/fuzz/fuzz_NAME.cpp).

    make_corpus.py --root REPO --out DIR

writes DIR/NAME/* for every target, from the repository's own files:
  nrrd           each datasets/*.nrrd header over the first voxels of its data
                 (4x4x4 of them), raw and gzip, big-endian for 16-bit types,
                 plus the real header over a truncated gzip stream;
  nrrd_detached  the same as .nhdr + data file pairs, with byte skips;
  fld            each datasets/fld/*.fld header over its first voxels;
  dat            .dat descriptions of the same voxels in every Format;
  scene          datasets/scenes, tests/golden/scenes, reference/*/scenes;
  tf, tf2d       datasets/tf, datasets/tf2d;
  viewer_script  scripts using every command;
  deck           datasets/decks and a deck with every kind of slide;
  report_text    students' names, file names, compiler logs and messages
                 (Latin-1, escape sequences, formulas, markup), NUL-separated;
  dicom          pairs of neighbouring 4x4 slices of the datasets as DICOM
                 files, written here byte by byte (explicit and implicit VR
                 little endian, explicit big endian, RLE lossless; with and
                 without a rescale), plus a single slice and a truncated one.
Every seed is small (under 4 KiB): the big volumes give only their headers
and a few hundred bytes. Two-file seeds join the files with the separator of
fuzz_common.h (kDataSeparator). Nothing is downloaded; the output is
regenerated from scratch on every run.
"""
import argparse
import glob
import gzip
import hashlib
import os
import shutil
import struct
import zlib

SEPARATOR = b"\n--voxlab-fuzz-data--\n"  # fuzz_common.h: kDataSeparator
DIMS = (4, 4, 4)
ELEMENT = {"uchar": 1, "ushort": 2, "short": 2, "float": 4}


class Corpus:
    def __init__(self, out):
        self.out = out

    def add(self, target, data):
        if isinstance(data, str):
            data = data.encode()
        folder = os.path.join(self.out, target)
        os.makedirs(folder, exist_ok=True)
        name = hashlib.sha1(data).hexdigest()[:16]
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)


def split_nrrd(path):
    """(header lines without the magic, the bytes after the blank line)."""
    with open(path, "rb") as f:
        head = f.read(1 << 16)
    end = head.index(b"\n\n")
    lines = head[:end].decode().split("\n")
    return lines[1:], head[end + 2:]


def first_voxels(nrrd_path, count):
    """The first `count` bytes of a gzip NRRD's voxels, and the header fields."""
    lines, rest = split_nrrd(nrrd_path)
    fields = dict(line.split(": ", 1) for line in lines if not line.startswith("#"))
    if fields.get("encoding") in ("gzip", "gz"):
        data = zlib.decompressobj(16 + zlib.MAX_WBITS).decompress(rest, count)
    else:
        data = rest[:count]
    return fields, lines, data


def nrrd_header(type_name, dims, encoding, extra=(), magic="NRRD0004"):
    lines = [magic, "# fuzz seed", "type: " + type_name, "dimension: 3",
             "sizes: %d %d %d" % dims, "spacings: 1 1 1"]
    if ELEMENT[type_name] > 1:
        lines.append("endian: little")
    lines.append("encoding: " + encoding)
    lines.extend(extra)
    return "\n".join(lines) + "\n"


def swapped(data, size):
    return b"".join(data[i:i + size][::-1] for i in range(0, len(data), size))


def as_float(data):
    return b"".join(struct.pack("<f", b / 7.0) for b in data)


def volumes(root):
    """(name, nrrd type, little-endian voxel bytes for DIMS) from the datasets."""
    n = DIMS[0] * DIMS[1] * DIMS[2]
    for path in sorted(glob.glob(os.path.join(root, "datasets", "*.nrrd"))):
        fields, _, _ = first_voxels(path, 0)
        t = {"uchar": "uchar", "ushort": "ushort", "short": "short", "float": "float"}.get(
            fields.get("type"), "uchar")
        _, _, data = first_voxels(path, n * ELEMENT[t])
        if len(data) == n * ELEMENT[t]:
            yield os.path.basename(path), t, data
            if t == "uchar" and "bonsai" in path:
                yield "float", "float", as_float(data)


def nrrd_seeds(root, corpus):
    for _, t, data in volumes(root):
        corpus.add("nrrd", nrrd_header(t, DIMS, "raw").encode() + b"\n" + data)
        corpus.add("nrrd", nrrd_header(t, DIMS, "gzip").encode() + b"\n" + gzip.compress(data, mtime=0))
        if ELEMENT[t] > 1:
            big = nrrd_header(t, DIMS, "raw").replace("endian: little", "endian: big")
            corpus.add("nrrd", big.encode() + b"\n" + swapped(data, ELEMENT[t]))
    # Real headers over truncated data, and other spellings the reader takes.
    for path in sorted(glob.glob(os.path.join(root, "datasets", "*.nrrd")))[:4]:
        with open(path, "rb") as f:
            head = f.read(1 << 16)
        corpus.add("nrrd", head[:head.index(b"\n\n") + 2 + 200])
    data = bytes(range(64))
    variants = [
        ["space directions: (1,0,0) (0,2,0) (0,0,0.5)", "kinds: domain domain domain", "key:=value"],
        ["byte skip: 0", "line skip: 0", "space origin: (0,0,0)"],
    ]
    for extra in variants:
        text = nrrd_header("uchar", DIMS, "raw", extra).replace("spacings: 1 1 1\n", "")
        corpus.add("nrrd", text.encode() + b"\n" + data)
    crlf = nrrd_header("uchar", DIMS, "raw", magic="NRRD0005").replace("\n", "\r\n")
    corpus.add("nrrd", crlf.encode() + b"\r\n" + data)


def detached_seeds(root, corpus):
    for i, (_, t, data) in enumerate(volumes(root)):
        for encoding in ("raw", "gzip"):
            payload = gzip.compress(data, mtime=0) if encoding == "gzip" else data
            skip = i % 3
            extra = ["data file: data.raw"] + (["byte skip: %d" % skip] if skip else [])
            header = nrrd_header(t, DIMS, encoding, extra)
            if encoding == "raw":
                payload = b"\x00" * skip + payload
            corpus.add("nrrd_detached", header.encode() + SEPARATOR + payload)
    header = nrrd_header("uchar", DIMS, "raw", ["datafile: data.raw"])
    corpus.add("nrrd_detached", header.encode() + SEPARATOR + bytes(64))
    corpus.add("nrrd_detached", nrrd_header("uchar", DIMS, "raw", ["data file: missing.raw"]))


def fld_seeds(root, corpus):
    n = DIMS[0] * DIMS[1] * DIMS[2]
    for path in sorted(glob.glob(os.path.join(root, "datasets", "fld", "*.fld"))):
        with open(path, "rb") as f:
            head = f.read(1 << 16)
        end = head.index(b"\f\f")
        lines = head[:end].decode("latin-1").split("\n")
        data = head[end + 2:end + 2 + 2 * n]
        for kind, size in (("byte", 1), ("short", 2)):
            out = []
            for line in lines:
                key = line.split("=", 1)[0].strip()
                if key in ("dim1", "dim2", "dim3"):
                    line = "%s=%d" % (key, DIMS[int(key[3]) - 1])
                elif key == "data":
                    line = "data=" + kind
                out.append(line)
            corpus.add("fld", "\n".join(out).encode("latin-1") + b"\f\f" + data[:size * n])
        corpus.add("fld", head[:end + 2 + 100])  # the real header, truncated data


def dat_seeds(root, corpus):
    spellings = {"uchar": ["UCHAR", "uint8", "BYTE"], "ushort": ["USHORT", "UINT16"],
                 "short": ["SHORT", "int16"], "float": ["FLOAT", "float32"]}
    for i, (name, t, data) in enumerate(volumes(root)):
        for spelling in spellings[t]:
            lines = ["ObjectFileName: volume.raw", "TaggedFileName: ---",
                     "Resolution: %d %d %d" % DIMS, "Format: " + spelling]
            if i % 2:
                lines.insert(3, "SliceThickness: 1 1 %g" % (1 + i / 4))
            if i % 3 == 0:
                lines.append("ObjectModel: I")
            eol = "\r\n" if i % 4 == 1 else "\n"
            corpus.add("dat", (eol.join(lines) + eol).encode() + SEPARATOR + data)


def copy_files(corpus, target, pattern):
    for path in sorted(glob.glob(pattern)):
        with open(path, "rb") as f:
            corpus.add(target, f.read())


def json_seeds(root, corpus):
    for pattern in ("datasets/scenes/*.json", "tests/golden/scenes/*.json", "reference/*/scenes/*.json"):
        copy_files(corpus, "scene", os.path.join(root, pattern))
    # Every key of the schema at once (README, "Scene files").
    corpus.add("scene", """{
  "dataset": "phantom:sphere:16", "renderer": "composite",
  "camera": {"azimuth": 30, "elevation": 20, "distance": 4, "fov": 30, "zoom": 1, "pan": [0.1, 0]},
  "projection": "perspective", "size": [64, 48],
  "sampling": {"step": 0.5, "interpolation": "nearest", "skip_empty_space": false},
  "window": [0, 1], "background": [0.1, 0.2, 0.3], "parameters": {"shading": true, "ka": 0.2},
  "transfer_function": [{"value": 0, "color": [0, 0, 0], "alpha": 0},
                        {"value": 1, "color": [1, 1, 1], "alpha": 1}],
  "tf2d": {"widgets": [{"type": "box", "value": [0, 1], "gradient": [0, 2], "alpha": 0.5,
                        "color": [1, 0, 0]}]},
  "roi": {"min": [0, 0, 2], "max": [16, 16, 14]},
  "cutting_plane": {"point": [8, 8, 8], "normal": [1, 0, 0],
                    "other_side": {"renderer": "mip", "transfer_function": "tf/bonsai.json",
                                   "parameters": {}}}
}""")
    corpus.add("scene", '{"dataset": "bonsai.nrrd", "camera": {"view": "-y", "zoom": 2}, '
                        '"tf2d": "tf2d/bonsai.json", "transfer_function": "tf/bonsai.json"}')
    copy_files(corpus, "tf", os.path.join(root, "datasets/tf/*.json"))
    corpus.add("tf", '[{"value": -1000, "color": [0, 0, 0], "alpha": 0}, '
                     '{"value": 40, "color": [1, 0.5, 0], "alpha": 0.2}, '
                     '{"value": 40, "color": [1, 1, 1], "alpha": 0.9}]')
    copy_files(corpus, "tf2d", os.path.join(root, "datasets/tf2d/*.json"))
    corpus.add("tf2d", '{"widgets": [{"type": "box", "value": [10, 20], "gradient": [0, 5], '
                       '"alpha": 0.3, "color": [0, 0.6, 0]}]}')


def deck_seeds(root, corpus):
    copy_files(corpus, "deck", os.path.join(root, "datasets/decks/*.json"))
    corpus.add("deck", """{"title": "every kind of slide", "slides": [
  {"scene": "scenes/default.json", "caption": "a scene file"},
  {"scene": "scenes/default.json", "renderer": "composite", "transfer_function": "tf/bonsai.json",
   "camera": {"azimuth": 10}, "parameters": {"shading": true}, "caption": "overridden"},
  {"scene": {"dataset": "phantom:sphere:16", "renderer": "iso"}, "caption": "inline"},
  {"scene": {"dataset": "phantom:sphere:16"}, "sampling": null}]}""")


def script_seeds(corpus):
    corpus.add("viewer_script", """# every command once
load phantom:sphere:32
scene scenes/default.json
renderer composite
param early_termination 0.9
param shading false
step 0.25
interpolation hardware
tf tf/bonsai.json
tf none
camera azimuth 10 elevation -20 distance 3 fov 40 zoom 1.5 pan 0.1 0.2
camera view -z projection orthographic
rotate 15 -5
drag 4 -2 10
window -10 300
skipping off
samples on
split difference
divider 0.25
right mip
implementation "my work/stage"
panel profile on
click 10 20
size 800 600
tf2d tf2d/bonsai.json
tf2d none
key right
key plus
ui-scale 1.5
slide 2
enlarge axial
enlarge off
wait 0
screenshot "out dir/shot.png"   # quoted
quit
""")
    corpus.add("viewer_script", "size 1280 800\nwait 3\ndrag 6 0 30\nwait 2\n")
    corpus.add("viewer_script", "load bonsai.nrrd\r\nsplit on\r\nright same\r\npanel tf2d off\r\n")


# ---- DICOM (PS3.5, PS3.10): just enough of a writer for seeds ----------------

EXPLICIT_LE, IMPLICIT_LE, EXPLICIT_BE = "1.2.840.10008.1.2.1", "1.2.840.10008.1.2", "1.2.840.10008.1.2.2"
RLE = "1.2.840.10008.1.2.5"
LONG_VRS = {"OB", "OW", "SQ", "UN", "UT"}


def dicom_element(group, element, vr, value, syntax):
    """One data element; `value` is bytes (already in the syntax's byte order)."""
    if len(value) % 2:
        value += b"\0" if vr in ("UI", "OB") else b" "
    big = syntax == EXPLICIT_BE and group != 2
    e = ">" if big else "<"
    head = struct.pack(e + "HH", group, element)
    if syntax == IMPLICIT_LE and group != 2:
        return head + struct.pack("<I", len(value)) + value
    if vr in LONG_VRS:
        return head + vr.encode() + b"\0\0" + struct.pack(e + "I", len(value)) + value
    return head + vr.encode() + struct.pack(e + "H", len(value)) + value


def rle_segment(data):
    """PackBits with literal runs only (PS3.5 G.3.1)."""
    out = b""
    for i in range(0, len(data), 128):
        chunk = data[i:i + 128]
        out += bytes([len(chunk) - 1]) + chunk
    return out + (b"\0" if len(out) % 2 else b"")


def dicom_file(k, pixels, bits, signed, syntax, rescale):
    """A 4x4 CT slice k at z = 1.5 k; pixels: 16 values."""
    big = syntax == EXPLICIT_BE
    us = lambda v: struct.pack(">H" if big else "<H", v)
    text = lambda t: t.encode()
    fmt = {(8, 0): "B", (8, 1): "b", (16, 0): "H", (16, 1): "h"}[(bits, signed)]
    raw = struct.pack((">" if big else "<") + fmt * 16, *pixels)
    elements = [
        (0x0008, 0x0016, "UI", text("1.2.840.10008.5.1.4.1.1.2")),
        (0x0008, 0x0018, "UI", text("1.2.826.0.1.3680043.8.498.%d" % (k + 1))),
        (0x0008, 0x0060, "CS", text("CT")),
        (0x0008, 0x103E, "LO", text("fuzz seed")),
        (0x0020, 0x000E, "UI", text("1.2.826.0.1.3680043.8.498.100")),
        (0x0020, 0x0013, "IS", text(str(9 - k))),
        (0x0020, 0x0032, "DS", text("-1.5\\2\\%g" % (1.5 * k))),
        (0x0020, 0x0037, "DS", text("1\\0\\0\\0\\1\\0")),
        (0x0028, 0x0002, "US", us(1)),
        (0x0028, 0x0004, "CS", text("MONOCHROME2")),
        (0x0028, 0x0010, "US", us(4)),
        (0x0028, 0x0011, "US", us(4)),
        (0x0028, 0x0030, "DS", text("0.5\\0.25")),
        (0x0028, 0x0100, "US", us(bits)),
        (0x0028, 0x0101, "US", us(bits)),
        (0x0028, 0x0102, "US", us(bits - 1)),
        (0x0028, 0x0103, "US", us(signed)),
    ]
    if rescale:
        elements += [(0x0028, 0x1052, "DS", text("-1024")), (0x0028, 0x1053, "DS", text("2"))]
    body = b"".join(dicom_element(g, e, vr, v, syntax) for g, e, vr, v in elements)
    if syntax == RLE:
        planes = [bytes(raw[i::bits // 8]) for i in range(bits // 8)][::-1]  # most significant byte first
        segments = [rle_segment(p) for p in planes]
        header = struct.pack("<I", len(segments))
        offset = 64
        for seg in segments:
            header += struct.pack("<I", offset)
            offset += len(seg)
        frame = header + bytes(64 - len(header)) + b"".join(segments)
        item = lambda data: struct.pack("<HHI", 0xFFFE, 0xE000, len(data)) + data
        body += struct.pack("<HH", 0x7FE0, 0x0010) + b"OB\0\0" + struct.pack("<I", 0xFFFFFFFF)
        body += item(b"") + item(frame) + struct.pack("<HHI", 0xFFFE, 0xE0DD, 0)
    else:
        body += dicom_element(0x7FE0, 0x0010, "OW" if bits == 16 else "OB", raw, syntax)
    meta = b"".join(dicom_element(2, e, vr, v, EXPLICIT_LE) for e, vr, v in [
        (0x0001, "OB", b"\0\1"), (0x0002, "UI", text("1.2.840.10008.5.1.4.1.1.2")),
        (0x0003, "UI", text("1.2.826.0.1.3680043.8.498.%d" % (k + 1))), (0x0010, "UI", text(syntax))])
    meta = dicom_element(2, 0, "UL", struct.pack("<I", len(meta)), EXPLICIT_LE) + meta
    return bytes(128) + b"DICM" + meta + body


def dicom_seeds(root, corpus):
    n = DIMS[0] * DIMS[1]  # one 4x4 slice
    for name, t, data in volumes(root):
        if t not in ("uchar", "ushort", "short"):
            continue
        size = ELEMENT[t]
        values = list(struct.unpack("<" + {"uchar": "B", "ushort": "H", "short": "h"}[t] * (2 * n),
                                    data[:2 * n * size]))
        bits, signed = (8, 0) if t == "uchar" else (16, 1 if t == "short" else 0)
        for syntax in (EXPLICIT_LE, IMPLICIT_LE, EXPLICIT_BE, RLE):
            for rescale in (False, True):
                a = dicom_file(0, values[:n], bits, signed, syntax, rescale)
                b = dicom_file(1, values[n:], bits, signed, syntax, rescale)
                corpus.add("dicom", a + SEPARATOR + b)
        one = dicom_file(0, values[:n], bits, signed, EXPLICIT_LE, False)
        corpus.add("dicom", one)  # one slice only
        corpus.add("dicom", one + SEPARATOR + one[:len(one) - 20])  # the second cut short


def report_text_seeds(corpus):
    """Texts a submission controls, split at NUL: name, file, log, message, example, note."""
    log = ("0:200014(9): error: `x' undeclared\n"
           "mip/mip.glsl:2:1: preprocessor error: #error caf\xe9 \x1b[2J\x1b]0;owned\x07\n"
           "texslice3d/proxy_geometry.cpp:1:2: error: #error na\xefve").encode("latin-1")
    corpus.add("report_text", b"\0".join([b"alice", b"mip/mip.glsl", log, b"6 of 6 items outside tolerance",
                                          b"n=(0,0,1) expected (1, 2) got (1, 3)", b"graded the stage folders found in sub/"]))
    corpus.add("report_text", b"\0".join([b"\x1b[31m=HYPERLINK(\"http://x\")", b"l\xe9a/sub\xe9/mip.glsl",
                                          b"<script>alert(1)</script>", b"-2+3, \"quoted\"\r\n@SUM(A1)",
                                          b"\t=1", b"\xed\xa0\x80\xf4\x90\x80\x80\xc0\xaf\xe2\x82"]))
    corpus.add("report_text", b"gradebook.csv\0\0" + b" " * 2000 + b"\0\xc2\x9b31m\x7f\x08")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", required=True, help="the voxlab repository")
    parser.add_argument("--out", required=True, help="folder to (re)create")
    args = parser.parse_args()
    shutil.rmtree(args.out, ignore_errors=True)
    corpus = Corpus(args.out)
    nrrd_seeds(args.root, corpus)
    detached_seeds(args.root, corpus)
    fld_seeds(args.root, corpus)
    dat_seeds(args.root, corpus)
    json_seeds(args.root, corpus)
    script_seeds(corpus)
    deck_seeds(args.root, corpus)
    dicom_seeds(args.root, corpus)
    report_text_seeds(corpus)
    for target in sorted(os.listdir(args.out)):
        print("fuzz corpus %-14s %3d seeds" % (target, len(os.listdir(os.path.join(args.out, target)))))


if __name__ == "__main__":
    main()
