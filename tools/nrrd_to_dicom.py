#!/usr/bin/python3
"""Writes a DICOM series (one axial slice per file) from a NRRD volume.

    /usr/bin/python3 tools/nrrd_to_dicom.py datasets/headsq.nrrd /tmp/headsq_dicom [options]

A demo and a test input for voxlab's DICOM loader, independent of it: the
NRRD header and its raw or gzip data are read with Python's standard library
only, and pydicom (Debian's python3-pydicom; run with /usr/bin/python3) writes
the files. Attached 3D NRRD files of type uchar, ushort or short are read
(every bundled dataset).

Layout: NRRD x (fastest) becomes the DICOM columns, y the rows, z the slices,
so voxlab loads the series back as the same grid. Pixel Spacing (0028,0030)
is written [y spacing, x spacing], slice k lies at Image Position (Patient)
(0020,0032) = (0, 0, k * z spacing) with Image Orientation (Patient)
(0020,0037) = 1\\0\\0\\0\\1\\0 (axial). Values are stored as
(value - intercept) / slope with Rescale Slope/Intercept (0028,1053)/(0028,1052)
(--slope, --intercept; an error if that is not a whole number that fits),
unsigned 16-bit when every stored value is >= 0, else signed. Files are written
and numbered from the top slice down (--order), so neither names nor Instance
Numbers follow z.
"""
import argparse
import gzip
import os
import struct
import sys

try:
    import numpy as np
    from pydicom.dataset import Dataset, FileMetaDataset
    from pydicom.uid import ExplicitVRLittleEndian, generate_uid
except ImportError as e:
    sys.exit(f"nrrd_to_dicom.py: cannot import pydicom/numpy ({e}); install python3-pydicom "
             f"and run with /usr/bin/python3")

NRRD_TYPES = {"uchar": "u1", "unsigned char": "u1", "uint8": "u1",
              "ushort": "u2", "unsigned short": "u2", "uint16": "u2",
              "short": "i2", "signed short": "i2", "int16": "i2"}


def read_nrrd(path):
    """(array[z][y][x], (sx, sy, sz), comment) of an attached NRRD."""
    with open(path, "rb") as f:
        data = f.read()
    if not data.startswith(b"NRRD"):
        sys.exit(f"{path}: not a NRRD file")
    end = data.find(b"\n\n")
    if end < 0:
        sys.exit(f"{path}: no blank line after the header")
    fields, comments = {}, []
    for line in data[:end].decode("latin-1").splitlines()[1:]:
        if line.startswith("#"):
            comments.append(line[1:].strip())
        elif ":" in line:
            key, value = line.split(":", 1)
            fields[key.strip().lower()] = value.lstrip("=").strip()
    if "data file" in fields or "datafile" in fields:
        sys.exit(f"{path}: detached data is not supported here")
    kind = NRRD_TYPES.get(fields.get("type", ""))
    if kind is None or fields.get("dimension") != "3":
        sys.exit(f"{path}: need a 3D uchar/ushort/short volume, got {fields.get('type')}")
    nx, ny, nz = (int(v) for v in fields["sizes"].split())
    spacing = tuple(float(v) for v in fields.get("spacings", "1 1 1").split())
    body = data[end + 2:]
    if fields.get("encoding") in ("gzip", "gz"):
        body = gzip.decompress(body)
    elif fields.get("encoding") != "raw":
        sys.exit(f"{path}: encoding {fields.get('encoding')} is not supported here")
    order = ">" if fields.get("endian") == "big" else "<"
    values = np.frombuffer(body, dtype=np.dtype(order + kind), count=nx * ny * nz)
    return values.reshape(nz, ny, nx).astype(np.int64), spacing, " ".join(comments)


def ds_string(x):
    """A decimal string (VR DS, at most 16 characters)."""
    for digits in range(15, 0, -1):
        text = f"{float(x):.{digits}g}"
        if len(text) <= 16:
            return text
    raise ValueError(x)


def stored_values(volume, slope, intercept):
    stored = (volume - intercept) / slope
    if not np.all(stored == np.round(stored)):
        sys.exit(f"nrrd_to_dicom.py: (value - {intercept}) / {slope} is not a whole number everywhere")
    stored = stored.astype(np.int64)
    dtype = np.uint16 if stored.min() >= 0 else np.int16
    info = np.iinfo(dtype)
    if stored.min() < info.min or stored.max() > info.max:
        sys.exit(f"nrrd_to_dicom.py: stored values {stored.min()}..{stored.max()} do not fit 16 bits")
    return stored.astype(dtype)


def slice_dataset(args, k, pixels, spacing, uids):
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"  # CT Image Storage
    meta.MediaStorageSOPInstanceUID = generate_uid(entropy_srcs=[uids["series"], str(k)])
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = Dataset()
    ds.file_meta = meta
    ds.is_little_endian, ds.is_implicit_VR = True, False
    ds.SOPClassUID, ds.SOPInstanceUID = meta.MediaStorageSOPClassUID, meta.MediaStorageSOPInstanceUID
    ds.Modality = args.modality
    ds.SeriesDescription = args.description
    ds.PatientName, ds.PatientID = "Anonymous^Demo", "voxlab-demo"
    ds.StudyInstanceUID, ds.SeriesInstanceUID = uids["study"], uids["series"]
    ds.FrameOfReferenceUID = uids["frame"]
    ds.ImagePositionPatient = [ds_string(0.0), ds_string(0.0), ds_string(k * spacing[2])]
    ds.ImageOrientationPatient = ["1", "0", "0", "0", "1", "0"]
    ds.PixelSpacing = [ds_string(spacing[1]), ds_string(spacing[0])]  # [row spacing (y), column spacing (x)]
    ds.SliceThickness = ds_string(spacing[2])
    ds.Rows, ds.Columns = pixels.shape
    ds.SamplesPerPixel = 1
    ds.PhotometricInterpretation = "MONOCHROME2"
    ds.BitsAllocated, ds.BitsStored, ds.HighBit = 16, 16, 15
    ds.PixelRepresentation = 1 if pixels.dtype == np.int16 else 0
    ds.RescaleSlope, ds.RescaleIntercept = ds_string(args.slope), ds_string(args.intercept)
    ds.RescaleType = args.rescale_type
    ds.PixelData = pixels.astype(pixels.dtype.newbyteorder("<")).tobytes()
    ds["PixelData"].VR = "OW"
    return ds


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("nrrd")
    p.add_argument("out")
    p.add_argument("--slope", type=float, default=1.0)
    p.add_argument("--intercept", type=float, default=-1024.0)
    p.add_argument("--modality", default="CT")
    p.add_argument("--rescale-type", default="US",
                   help="(0028,1054): US (unspecified, the default: the bundled CTs are not in HU) or HU")
    p.add_argument("--description", default="")
    p.add_argument("--order", choices=["ascending", "descending"], default="descending",
                   help="the order files are written, named and numbered in, by position")
    args = p.parse_args()
    volume, spacing, comment = read_nrrd(args.nrrd)
    if not args.description:
        args.description = (os.path.basename(args.nrrd) + ": " + comment)[:64]
    stored = stored_values(volume, args.slope, args.intercept)
    os.makedirs(args.out, exist_ok=True)
    name = os.path.basename(args.nrrd)
    uids = {key: generate_uid(entropy_srcs=[key, name]) for key in ("study", "series", "frame")}
    ks = list(range(stored.shape[0]))
    if args.order == "descending":
        ks.reverse()
    for index, k in enumerate(ks):
        ds = slice_dataset(args, k, stored[k], spacing, uids)
        ds.InstanceNumber = index + 1
        ds.save_as(os.path.join(args.out, f"IM{index + 1:04d}.dcm"), write_like_original=False)
    print(f"{args.out}: {len(ks)} slices of {stored.shape[2]}x{stored.shape[1]} {stored.dtype}, "
          f"spacing {spacing[0]:g} {spacing[1]:g} {spacing[2]:g}, value = {args.slope:g} x stored "
          f"{'-' if args.intercept < 0 else '+'} {abs(args.intercept):g}")


if __name__ == "__main__":
    main()
