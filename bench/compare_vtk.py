#!/usr/bin/python3
"""Times one scene with VTK's GPU ray caster and with voxlab, on the same machine.

    xvfb-run -a /usr/bin/python3 bench/compare_vtk.py [--renderer composite|mip] [--frames N]
                                                      [--size 512] [--step 0.5] [--out DIR] [--json]

The peer is vtkGPUVolumeRayCastMapper (Debian 12: python3-vtk9) on the same
OpenGL (Mesa llvmpipe under Xvfb here). Settings are matched: the same
volume (bonsai.nrrd), image size, perspective orbit view (azimuth 35,
elevation 25, fov 30, distance 4 bounding-sphere radii), sample distance
(VTK's SampleDistance = step x smallest spacing, automatic adjustment off,
no jitter), transfer function (datasets/tf/bonsai.json; VTK's scalar opacity
unit distance = the smallest spacing, the same "opacity per unit length" as
voxlab's), trilinear interpolation, black background. voxlab's voxel i is
centred at (i + 1/2) spacing, so the VTK volume's origin is half a voxel in.

VTK filters the volume with the GPU's trilinear filtering (a 3D texture
read with linear filtering); voxlab's matching setting is `--interpolation
hardware`. voxlab is timed in three set-ups: that one, the same without
empty-space skipping, and the shader's own trilinear sampling (the sampling
stage, exact in float) with skipping.

Every run is N frames after a warm-up, the camera turning 0.5 degrees a
frame. It prints each median and its ratio to VTK's, and writes
DIR/vtk.png, DIR/voxlab.png (the matched set-up) and DIR/side_by_side.png
(VTK left). Ratios, not absolute times, are what a shared machine measures
reliably; --json prints the figures as JSON as well.
"""
import argparse
import gzip
import json
import math
import os
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

try:
    import vtk
except ImportError:
    sys.exit("compare_vtk.py: VTK is missing (Debian 12: apt-get install python3-vtk9; run with /usr/bin/python3)")


def read_uchar_nrrd(path):
    """Sizes, spacings and voxels of a uchar NRRD with raw or gzip encoding."""
    data = open(path, "rb").read()
    end = data.index(b"\n\n")
    fields = {}
    for line in data[:end].decode("ascii", "replace").splitlines()[1:]:
        if ":" in line and not line.startswith("#"):
            key, value = line.split(":", 1)
            fields[key.strip()] = value.strip()
    if fields.get("type") not in ("uchar", "unsigned char", "uint8"):
        sys.exit(f"compare_vtk.py: {path}: expected uchar data")
    dims = [int(x) for x in fields["sizes"].split()]
    spacing = [float(x) for x in fields.get("spacings", "1 1 1").split()]
    raw = data[end + 2:]
    if fields.get("encoding") == "gzip":
        raw = gzip.decompress(raw)
    return dims, spacing, raw


def orbit_basis(azimuth, elevation):
    """voxlab's orbit camera (framework/src/render/camera.cpp): forward and image-down."""
    az, el = math.radians(azimuth), math.radians(elevation)
    forward = (math.sin(az) * math.cos(el), math.sin(el), math.cos(az) * math.cos(el))
    up = (math.sin(az) * math.sin(el), -math.cos(el), math.cos(az) * math.sin(el))
    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    def unit(a):
        n = math.sqrt(sum(x * x for x in a))
        return tuple(x / n for x in a)
    right = unit(cross(forward, up))
    down = unit(cross(forward, right))
    return forward, down


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--renderer", default="composite", choices=["composite", "mip"])
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--step", type=float, default=0.5)
    ap.add_argument("--out", default="/tmp/voxlab_compare_vtk")
    ap.add_argument("--voxlab", default=os.path.join(ROOT, "build", "bin", "voxlab"))
    ap.add_argument("--json", action="store_true", help="also print the figures as JSON")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    azimuth, elevation, fov, distance = 35.0, 25.0, 30.0, 4.0

    # VTK's NRRD reader does not read gzip encoding: decode it here.
    dims, spacing, raw = read_uchar_nrrd(os.path.join(ROOT, "datasets", "bonsai.nrrd"))
    importer = vtk.vtkImageImport()
    importer.CopyImportVoidPointer(raw, len(raw))
    importer.SetDataScalarTypeToUnsignedChar()
    importer.SetNumberOfScalarComponents(1)
    importer.SetWholeExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1)
    importer.SetDataExtentToWholeExtent()
    importer.SetDataSpacing(*spacing)
    importer.SetDataOrigin(*(0.5 * s for s in spacing))
    importer.Update()
    image = importer.GetOutput()
    extent = [d * s for d, s in zip(dims, spacing)]
    centre = [0.5 * e for e in extent]
    radius = 0.5 * math.sqrt(sum(e * e for e in extent))
    min_spacing = min(spacing)

    tf = json.load(open(os.path.join(ROOT, "datasets", "tf", "bonsai.json")))["points"]
    colour = vtk.vtkColorTransferFunction()
    opacity = vtk.vtkPiecewiseFunction()
    if args.renderer == "composite":
        for p in tf:
            colour.AddRGBPoint(p["value"], *p["color"])
            opacity.AddPoint(p["value"], p["alpha"])
    else:  # MIP shows the grey window 0..255
        colour.AddRGBPoint(0, 0, 0, 0)
        colour.AddRGBPoint(255, 1, 1, 1)
        opacity.AddPoint(0, 1.0)
        opacity.AddPoint(255, 1.0)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(colour)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(min_spacing)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOff()

    mapper = vtk.vtkGPUVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetSampleDistance(args.step * min_spacing)
    mapper.SetUseJittering(0)
    if args.renderer == "mip":
        mapper.SetBlendModeToMaximumIntensity()
    else:
        mapper.SetBlendModeToComposite()
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0, 0, 0)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    camera.SetViewAngle(fov)

    def place(az):
        forward, down = orbit_basis(az, elevation)
        camera.SetFocalPoint(*centre)
        camera.SetPosition(*[c - f * distance * radius for c, f in zip(centre, forward)])
        camera.SetViewUp(*[-d for d in down])
        renderer.ResetCameraClippingRange()

    times = []
    for f in range(2 + args.frames):
        place(azimuth + (0.5 * (f - 1) if f >= 2 else 0.0))
        t0 = time.perf_counter()
        window.Render()
        window.WaitForCompletion()
        if f >= 2:
            times.append((time.perf_counter() - t0) * 1000.0)
    place(azimuth)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(os.path.join(args.out, "vtk.png"))
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()

    scene = ["--dataset", "bonsai.nrrd", "--renderer", args.renderer, "--size", f"{args.size}x{args.size}",
             "--step", str(args.step), "--azimuth", str(azimuth), "--elevation", str(elevation), "--fov", str(fov),
             "--distance", str(distance), "--projection", "perspective"]
    if args.renderer == "composite":
        scene += ["--tf", "tf/bonsai.json"]
    else:
        scene += ["--window", "0,255"]
    setups = [("GPU trilinear filtering, skipping on (matched)", ["--interpolation", "hardware"]),
              ("GPU trilinear filtering, skipping off", ["--interpolation", "hardware", "--skip-empty-space", "off"]),
              ("shader trilinear, skipping on", ["--interpolation", "trilinear"])]
    voxlab = []
    for name, options in setups:
        bench = subprocess.run([args.voxlab, "bench", *scene, *options, "--frames", str(args.frames), "--json"],
                               check=True, capture_output=True, text=True)
        voxlab.append((name, json.loads(bench.stdout)))
    subprocess.run([args.voxlab, "render", *scene, *setups[0][1], "--out", os.path.join(args.out, "voxlab.png")],
                   check=True, capture_output=True)

    png = vtk.vtkPNGReader()
    png.SetFileName(os.path.join(args.out, "voxlab.png"))
    left = vtk.vtkPNGReader()
    left.SetFileName(os.path.join(args.out, "vtk.png"))
    rgb = vtk.vtkImageExtractComponents()  # both as RGB
    rgb.SetInputConnection(left.GetOutputPort())
    rgb.SetComponents(0, 1, 2)
    both = vtk.vtkImageAppend()
    both.SetAppendAxis(0)
    both.AddInputConnection(rgb.GetOutputPort())
    both.AddInputConnection(png.GetOutputPort())
    out = vtk.vtkPNGWriter()
    out.SetFileName(os.path.join(args.out, "side_by_side.png"))
    out.SetInputConnection(both.GetOutputPort())
    out.Write()

    vtk_median = statistics.median(times)
    print(f"bonsai {args.renderer}, {args.size}x{args.size}, step {args.step}, {args.frames} frames")
    print(f"VTK {vtk.vtkVersion.GetVTKVersion()} GPU ray caster: median {vtk_median:.1f} ms/frame")
    for name, figures in voxlab:
        skipped = figures.get("skipped_fraction", 0.0)
        print(f"voxlab, {name}: median {figures['median_ms']:.1f} ms/frame, ratio to VTK "
              f"{figures['median_ms'] / vtk_median:.2f} ({100 * skipped:.0f}% of samples skipped)")
    print(f"gl: {voxlab[0][1]['gl']}")
    print(f"images: {os.path.join(args.out, 'side_by_side.png')} (VTK left, voxlab right)")
    if args.json:
        print(json.dumps({"renderer": args.renderer, "size": args.size, "step": args.step, "frames": args.frames,
                          "vtk_median_ms": vtk_median,
                          "voxlab": [{"setup": name, "median_ms": f["median_ms"],
                                      "ratio": f["median_ms"] / vtk_median,
                                      "skipped_fraction": f.get("skipped_fraction", 0.0)} for name, f in voxlab]},
                         indent=2))

if __name__ == "__main__":
    main()
