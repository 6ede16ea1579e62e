#!/usr/bin/python3
"""Writes a small DICOM series with known voxels, for tests/test_dicom.cpp.

    /usr/bin/python3 tests/dicom/make_series.py OUT_DIR [options]

Independent of voxlab's loader: pydicom (Debian's python3-pydicom) writes the
files, and nothing here is shared with the C++ side. Run it with Debian's
/usr/bin/python3 (the first python3 on PATH may lack Debian's packages); a
missing pydicom is a failure (exit 3 with one line), never a silent skip.

The series' voxels. Voxel (i, j, k) -- i the DICOM column, j the row, k the
slice counted in increasing position along the slice normal
n = row cosine x column cosine -- stores

    stored(i, j, k) = i + 10*j + 100*k + BASE          (--base, default 0)

and the file says Rescale Slope (0028,1053) = --slope and Rescale Intercept
(0028,1052) = --intercept, so the value a loader should give is
slope * stored + intercept. Slice k lies at Image Position (Patient)
(0020,0032) = ORIGIN + k * SPACING * n.

Files are named in the order they are written (--order: shuffled by
default) and their Instance Numbers (0020,0013) are deliberately misleading
(the reverse of the write order), so that neither the names nor the numbers
give the slice order; only the positions do.

Faults for the error tests: --drop K (leave out slice K), --second-series
(a second series of two slices in the same folder), --odd-size K (slice K has
one more column), --omit KEYWORD (delete an attribute from every file,
e.g. ImagePositionPatient, PixelSpacing, Rows, PixelData),
--transfer-syntax UID (encapsulated pixel data under that transfer syntax,
e.g. MPEG2 1.2.840.10008.1.2.4.100 or a made-up UID), --odd-orientation K
(slice K sagittal), --odd-bits K (slice K stored with 8 bits), --odd-signed K
(slice K with the other Pixel Representation), --shift K MM (slice K moved
MM along the normal).
"""
import argparse
import os
import random
import sys

try:
    import numpy as np
    import pydicom
    from pydicom.dataset import Dataset, FileMetaDataset
    from pydicom.encaps import encapsulate
    from pydicom.uid import ExplicitVRLittleEndian, ImplicitVRLittleEndian, generate_uid
except ImportError as e:  # a test must fail loudly, not skip
    print(f"make_series.py: cannot import pydicom/numpy ({e}); install python3-pydicom python3-numpy "
          f"and run with /usr/bin/python3", file=sys.stderr)
    sys.exit(3)

CT_IMAGE_STORAGE = "1.2.840.10008.5.1.4.1.1.2"
MR_IMAGE_STORAGE = "1.2.840.10008.5.1.4.1.1.4"


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("--cols", type=int, default=5)
    p.add_argument("--rows", type=int, default=4)
    p.add_argument("--slices", type=int, default=3)
    p.add_argument("--pixel-spacing", type=float, nargs=2, default=[1.0, 1.0],
                   metavar=("ROW", "COL"), help="(0028,0030): row spacing (y), column spacing (x)")
    p.add_argument("--spacing", type=float, default=1.0, help="slice spacing along the normal")
    p.add_argument("--origin", type=float, nargs=3, default=[-10.0, 20.0, 30.0])
    p.add_argument("--orientation", type=float, nargs=6, default=[1, 0, 0, 0, 1, 0])
    p.add_argument("--order", choices=["shuffled", "ascending", "descending"], default="shuffled",
                   help="the order files are written (and named) in, by position")
    p.add_argument("--stored", choices=["uint8", "uint16", "int16"], default="int16")
    p.add_argument("--bits-stored", type=int, default=0, help="(0028,0101), default: all bits")
    p.add_argument("--base", type=int, default=0)
    p.add_argument("--slope", type=str, default="1")
    p.add_argument("--intercept", type=str, default="0")
    p.add_argument("--no-rescale", action="store_true", help="leave out slope and intercept")
    p.add_argument("--modality", default="CT")
    p.add_argument("--description", default="voxlab test series")
    p.add_argument("--big-endian", action="store_true")
    p.add_argument("--implicit", action="store_true", help="Implicit VR Little Endian")
    p.add_argument("--no-preamble", action="store_true")
    p.add_argument("--extension", default=".dcm")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--drop", type=int, action="append", default=[])
    p.add_argument("--second-series", action="store_true")
    p.add_argument("--odd-size", type=int, default=-1)
    p.add_argument("--odd-orientation", type=int, default=-1)
    p.add_argument("--odd-bits", type=int, default=-1)
    p.add_argument("--odd-signed", type=int, default=-1)
    p.add_argument("--shift", type=float, nargs=2, default=[-1, 0], metavar=("K", "MM"))
    p.add_argument("--omit", action="append", default=[])
    p.add_argument("--transfer-syntax", default="")
    p.add_argument("--extra-file", action="store_true", help="also write a README.txt (not DICOM)")
    return p.parse_args()


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def ds_string(x):
    """A decimal string (VR DS, at most 16 characters), as precise as fits."""
    if isinstance(x, str):
        return x
    for digits in range(15, 0, -1):
        text = f"{float(x):.{digits}g}"
        if len(text) <= 16:
            return text
    raise ValueError(x)


def slice_dataset(args, k, series_uid, study_uid, frame_uid, cols, rows, orientation, stored_type, rng):
    r, c = orientation[:3], orientation[3:]
    n = cross(r, c)
    along = k * args.spacing + (args.shift[1] if k == int(args.shift[0]) else 0.0)
    pos = [args.origin[a] + along * n[a] for a in range(3)]

    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = CT_IMAGE_STORAGE if args.modality == "CT" else MR_IMAGE_STORAGE
    meta.MediaStorageSOPInstanceUID = generate_uid(entropy_srcs=[series_uid, str(k)])
    meta.TransferSyntaxUID = ImplicitVRLittleEndian if args.implicit else ExplicitVRLittleEndian
    if args.big_endian:
        meta.TransferSyntaxUID = "1.2.840.10008.1.2.2"
    if args.transfer_syntax:
        meta.TransferSyntaxUID = args.transfer_syntax

    ds = Dataset()
    ds.file_meta = meta
    ds.is_little_endian = not args.big_endian
    ds.is_implicit_VR = args.implicit
    ds.SOPClassUID = meta.MediaStorageSOPClassUID
    ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
    ds.Modality = args.modality
    ds.SeriesDescription = args.description
    ds.PatientName = "Test^Phantom"
    ds.PatientID = "voxlab-0001"
    ds.StudyInstanceUID = study_uid
    ds.SeriesInstanceUID = series_uid
    ds.FrameOfReferenceUID = frame_uid
    ds.SeriesNumber = 7
    ds.ImagePositionPatient = [ds_string(v) for v in pos]
    ds.ImageOrientationPatient = [ds_string(v) for v in orientation]
    ds.PixelSpacing = [ds_string(args.pixel_spacing[0]), ds_string(args.pixel_spacing[1])]
    ds.SliceThickness = ds_string(args.spacing)
    ds.Rows = rows
    ds.Columns = cols
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    bits = {"uint8": 8, "uint16": 16, "int16": 16}[stored_type]
    ds.BitsAllocated = bits
    ds.BitsStored = args.bits_stored if args.bits_stored and bits == 16 else bits
    ds.HighBit = ds.BitsStored - 1
    ds.PixelRepresentation = 1 if stored_type == "int16" else 0
    if not args.no_rescale:
        ds.RescaleIntercept = args.intercept
        ds.RescaleSlope = args.slope
        ds.RescaleType = "HU" if args.modality == "CT" else "US"

    j, i = np.mgrid[0:rows, 0:cols]
    stored = i + 10 * j + 100 * k + args.base
    dtype = {"uint8": np.uint8, "uint16": np.uint16, "int16": np.int16}[stored_type]
    info = np.iinfo(dtype)
    if stored.min() < info.min or stored.max() > info.max:
        sys.exit(f"make_series.py: stored values {stored.min()}..{stored.max()} do not fit {stored_type}")
    pixels = stored.astype(dtype)
    if args.bits_stored and bits == 16 and stored_type == "uint16":
        # Garbage in the unused high bits, which a loader must mask off.
        pixels = pixels | np.uint16(0xF000 & (0xFFFF << args.bits_stored))
    data = pixels.astype(pixels.dtype.newbyteorder(">" if args.big_endian else "<")).tobytes()
    if args.transfer_syntax:
        ds.PixelData = encapsulate([data + (b"\0" if len(data) % 2 else b"")])
        ds["PixelData"].VR = "OB"
        ds["PixelData"].is_undefined_length = True
    else:
        ds.PixelData = data
        ds["PixelData"].VR = "OW" if bits == 16 else "OB"
    return ds


def write_series(args, out, series_uid, slices, rng, file_prefix):
    study_uid = generate_uid(entropy_srcs=["study", str(args.seed)])
    frame_uid = generate_uid(entropy_srcs=["frame", str(args.seed)])
    ks = [k for k in range(slices) if k not in args.drop]
    if args.order == "shuffled":
        rng.shuffle(ks)
    elif args.order == "descending":
        ks.reverse()
    for index, k in enumerate(ks):
        cols = args.cols + (1 if k == args.odd_size else 0)
        orientation = list(args.orientation)
        if k == args.odd_orientation:
            orientation = [0, 1, 0, 0, 0, -1]  # sagittal among axial slices
        stored_type = "uint8" if k == args.odd_bits else args.stored
        if k == args.odd_signed:
            stored_type = {"int16": "uint16", "uint16": "int16"}.get(stored_type, stored_type)
        ds = slice_dataset(args, k, series_uid, study_uid, frame_uid, cols, args.rows, orientation,
                           stored_type, rng)
        ds.InstanceNumber = len(ks) - index  # misleading on purpose
        for keyword in args.omit:
            if keyword in ds:
                delattr(ds, keyword)
        name = os.path.join(out, f"{file_prefix}{index:03d}{args.extension}")
        if args.no_preamble:
            ds.preamble = None
            ds.save_as(name, write_like_original=True)
        else:
            ds.save_as(name, write_like_original=False)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    rng = random.Random(args.seed)
    series_uid = generate_uid(entropy_srcs=["series", str(args.seed)])
    write_series(args, args.out, series_uid, args.slices, rng, "IM")
    if args.second_series:
        other = generate_uid(entropy_srcs=["second series", str(args.seed)])
        args.drop = []
        write_series(args, args.out, other, 2, rng, "SE2_")
    if args.extra_file:
        with open(os.path.join(args.out, "README.txt"), "w") as f:
            f.write("not a DICOM file\n")


if __name__ == "__main__":
    main()
