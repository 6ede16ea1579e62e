#!/usr/bin/python3
"""Times voxlab against VTK's GPU ray caster on the same machine, the issue's five figures in one run.

    xvfb-run -a /usr/bin/python3 bench/compare_vtk.py [--only composite,shaded,iso,mip,tf2d] [--frames N]
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

The comparisons, each against the VTK mode that does the same work:
  composite  unshaded compositing; voxlab with the GPU's trilinear filtering
             (VTK's own), skipping on (target: at most 0.25 x VTK)
  shaded     the same with gradient shading: VTK's ShadeOn (ambient 0.2,
             diffuse 0.7, specular 0.3, power 24, its headlight), voxlab's
             shading parameter with the same coefficients (target 0.5 x)
  iso        VTK's isosurface blend mode (shaded) at the isovalue 60 against
             voxlab's iso renderer with 8 bisection steps (target 0.5 x)
  mip        maximum intensity through the shader's own trilinear sampling
             (the sampling stage, exact in float) against VTK's MIP (0.5 x)
  tf2d       the 2D transfer function (datasets/tf2d/bonsai.json), which VTK
             has no mode for: its time alone, against the 1 s target
For composite and MIP the other voxlab set-ups are timed as well.

Every run is N frames after a warm-up, the camera turning 0.5 degrees a
frame. It prints each median and its ratio to VTK's, and writes DIR/vtk_<mode>.png,
DIR/voxlab_<mode>.png and DIR/side_by_side_<mode>.png (VTK left). Ratios, not absolute
times, are what a shared machine measures reliably; --json prints the
figures as JSON as well.
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
    """voxlab's orbit camera (framework/src/volume/camera.cpp): forward and image-down."""
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


ISOVALUE = 60.0
LIGHT = {"ka": 0.2, "kd": 0.7, "ks": 0.3, "shininess": 24.0}
TARGETS = {"composite": 0.25, "shaded": 0.5, "iso": 0.5, "mip": 0.5}
TF2D_TARGET_MS = 1000.0


class VtkScene:
    """bonsai in VTK's GPU ray caster, set up once, switched between the modes."""

    def __init__(self, size, step):
        dims, spacing, raw = read_uchar_nrrd(os.path.join(ROOT, "datasets", "bonsai.nrrd"))
        # VTK's NRRD reader does not read gzip encoding. The importer owns the
        # voxels its output points at: it must live as long as the scene.
        self.importer = importer = vtk.vtkImageImport()
        importer.CopyImportVoidPointer(raw, len(raw))
        importer.SetDataScalarTypeToUnsignedChar()
        importer.SetNumberOfScalarComponents(1)
        importer.SetWholeExtent(0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1)
        importer.SetDataExtentToWholeExtent()
        importer.SetDataSpacing(*spacing)
        importer.SetDataOrigin(*(0.5 * s for s in spacing))
        importer.Update()
        self.image = importer.GetOutput()
        extent = [d * s for d, s in zip(dims, spacing)]
        self.centre = [0.5 * e for e in extent]
        self.radius = 0.5 * math.sqrt(sum(e * e for e in extent))
        self.min_spacing = min(spacing)
        self.prop = vtk.vtkVolumeProperty()
        self.prop.SetScalarOpacityUnitDistance(self.min_spacing)
        self.prop.SetInterpolationTypeToLinear()
        self.mapper = vtk.vtkGPUVolumeRayCastMapper()
        self.mapper.SetInputData(self.image)
        self.mapper.SetAutoAdjustSampleDistances(0)
        self.mapper.SetSampleDistance(step * self.min_spacing)
        self.mapper.SetUseJittering(0)
        volume = vtk.vtkVolume()
        volume.SetMapper(self.mapper)
        volume.SetProperty(self.prop)
        self.renderer = vtk.vtkRenderer()
        self.renderer.AddVolume(volume)
        self.renderer.SetBackground(0, 0, 0)
        self.window = vtk.vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(size, size)
        self.window.AddRenderer(self.renderer)
        self.camera = self.renderer.GetActiveCamera()
        self.camera.SetViewAngle(FOV)

    def set_mode(self, mode):
        colour, opacity = vtk.vtkColorTransferFunction(), vtk.vtkPiecewiseFunction()
        if mode in ("composite", "shaded"):
            for p in json.load(open(os.path.join(ROOT, "datasets", "tf", "bonsai.json")))["points"]:
                colour.AddRGBPoint(p["value"], *p["color"])
                opacity.AddPoint(p["value"], p["alpha"])
        elif mode == "iso":  # voxlab's default surface colour, opaque
            colour.AddRGBPoint(0, 0.9, 0.85, 0.75)
            colour.AddRGBPoint(255, 0.9, 0.85, 0.75)
            opacity.AddPoint(0, 1.0)
            opacity.AddPoint(255, 1.0)
        else:  # MIP shows the grey window 0..255
            colour.AddRGBPoint(0, 0, 0, 0)
            colour.AddRGBPoint(255, 1, 1, 1)
            opacity.AddPoint(0, 1.0)
            opacity.AddPoint(255, 1.0)
        self.prop.SetColor(colour)
        self.prop.SetScalarOpacity(opacity)
        if mode in ("shaded", "iso"):
            self.prop.ShadeOn()
            self.prop.SetAmbient(LIGHT["ka"])
            self.prop.SetDiffuse(LIGHT["kd"])
            self.prop.SetSpecular(LIGHT["ks"])
            self.prop.SetSpecularPower(LIGHT["shininess"])
        else:
            self.prop.ShadeOff()
        if mode == "mip":
            self.mapper.SetBlendModeToMaximumIntensity()
        elif mode == "iso":
            self.mapper.SetBlendModeToIsoSurface()
            self.prop.GetIsoSurfaceValues().SetValue(0, ISOVALUE)
        else:
            self.mapper.SetBlendModeToComposite()

    def place(self, az):
        forward, down = orbit_basis(az, ELEVATION)
        self.camera.SetFocalPoint(*self.centre)
        self.camera.SetPosition(*[c - f * DISTANCE * self.radius for c, f in zip(self.centre, forward)])
        self.camera.SetViewUp(*[-d for d in down])
        self.renderer.ResetCameraClippingRange()

    def time(self, mode, frames, png):
        self.set_mode(mode)
        times = []
        for f in range(2 + frames):
            self.place(AZIMUTH + (0.5 * (f - 1) if f >= 2 else 0.0))
            t0 = time.perf_counter()
            self.window.Render()
            self.window.WaitForCompletion()
            if f >= 2:
                times.append((time.perf_counter() - t0) * 1000.0)
        self.place(AZIMUTH)
        self.window.Render()
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.ReadFrontBufferOff()
        grab.Update()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(png)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        return statistics.median(times)


AZIMUTH, ELEVATION, FOV, DISTANCE = 35.0, 25.0, 30.0, 4.0


def voxlab_scene(args, mode):
    """The voxlab options of a mode, and its set-ups (the first is the one compared)."""
    renderer = {"shaded": "composite", "tf2d": "tf2d"}.get(mode, mode)
    scene = ["--dataset", "bonsai.nrrd", "--renderer", renderer, "--size", f"{args.size}x{args.size}",
             "--step", str(args.step), "--azimuth", str(AZIMUTH), "--elevation", str(ELEVATION), "--fov", str(FOV),
             "--distance", str(DISTANCE), "--projection", "perspective"]
    light = [x for k, v in LIGHT.items() for x in ("--param", f"{k}={v}")]
    if mode == "composite":
        return scene + ["--tf", "tf/bonsai.json"], [
            ("GPU trilinear filtering, skipping on (matched)", ["--interpolation", "hardware"]),
            ("GPU trilinear filtering, skipping off", ["--interpolation", "hardware", "--skip-empty-space", "off"]),
            ("shader trilinear, skipping on", ["--interpolation", "trilinear"])]
    if mode == "shaded":
        return scene + ["--tf", "tf/bonsai.json", "--param", "shading=1", *light], [
            ("GPU trilinear filtering, shaded", ["--interpolation", "hardware"])]
    if mode == "iso":
        return scene + ["--param", f"isovalue={ISOVALUE}", *light], [
            ("GPU trilinear filtering, 8 bisection steps", ["--interpolation", "hardware"])]
    if mode == "mip":
        return scene + ["--window", "0,255"], [
            ("shader trilinear, skipping on", ["--interpolation", "trilinear"]),
            ("GPU trilinear filtering, skipping on", ["--interpolation", "hardware"])]
    return scene + ["--tf2d", "tf2d/bonsai.json"], [("GPU trilinear filtering", ["--interpolation", "hardware"])]


def time_voxlab(args, mode):
    scene, setups = voxlab_scene(args, mode)
    results = []
    for name, options in setups:
        bench = subprocess.run([args.voxlab, "bench", *scene, *options, "--frames", str(args.frames), "--json"],
                               check=True, capture_output=True, text=True)
        results.append((name, json.loads(bench.stdout)))
    subprocess.run([args.voxlab, "render", *scene, *setups[0][1], "--out",
                    os.path.join(args.out, f"voxlab_{mode}.png")], check=True, capture_output=True)
    return results


def side_by_side(out, mode):
    reader = {}
    for who in ("vtk", "voxlab"):
        png = vtk.vtkPNGReader()
        png.SetFileName(os.path.join(out, f"{who}_{mode}.png"))
        rgb = vtk.vtkImageExtractComponents()  # both as RGB
        rgb.SetInputConnection(png.GetOutputPort())
        rgb.SetComponents(0, 1, 2)
        reader[who] = rgb
    both = vtk.vtkImageAppend()
    both.SetAppendAxis(0)
    both.AddInputConnection(reader["vtk"].GetOutputPort())
    both.AddInputConnection(reader["voxlab"].GetOutputPort())
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(os.path.join(out, f"side_by_side_{mode}.png"))
    writer.SetInputConnection(both.GetOutputPort())
    writer.Write()


def main():
    modes = ["composite", "shaded", "iso", "mip", "tf2d"]
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("--only", default=",".join(modes), help="comma-separated modes (default: all five)")
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--step", type=float, default=0.5)
    ap.add_argument("--out", default="/tmp/voxlab_compare_vtk")
    ap.add_argument("--voxlab", default=os.path.join(ROOT, "build", "bin", "voxlab"))
    ap.add_argument("--json", action="store_true", help="also print the figures as JSON")
    args = ap.parse_args()
    chosen = [m for m in args.only.split(",") if m]
    for m in chosen:
        if m not in modes:
            sys.exit(f"compare_vtk.py: --only: unknown mode '{m}' (expected {', '.join(modes)})")
    os.makedirs(args.out, exist_ok=True)
    peer = VtkScene(args.size, args.step)
    report, gl = [], ""
    print(f"bonsai, {args.size}x{args.size}, step {args.step}, {args.frames} frames; "
          f"VTK {vtk.vtkVersion.GetVTKVersion()} GPU ray caster")
    for mode in chosen:
        vtk_ms = None
        if mode != "tf2d":
            vtk_ms = peer.time(mode, args.frames, os.path.join(args.out, f"vtk_{mode}.png"))
        results = time_voxlab(args, mode)
        gl = results[0][1]["gl"]
        if vtk_ms is not None:
            side_by_side(args.out, mode)
            print(f"{mode}: VTK median {vtk_ms:.1f} ms/frame")
        for name, f in results:
            ratio = f["median_ms"] / vtk_ms if vtk_ms else None
            line = f"  voxlab, {name}: median {f['median_ms']:.1f} ms/frame"
            if ratio is not None:
                line += f", ratio to VTK {ratio:.2f}"
            print(line + f" ({100 * f.get('skipped_fraction', 0.0):.0f}% of samples skipped)")
            report.append({"mode": mode, "setup": name, "median_ms": f["median_ms"], "vtk_median_ms": vtk_ms,
                           "ratio": ratio, "skipped_fraction": f.get("skipped_fraction", 0.0)})
    print("summary (the first set-up of each mode against its target):")
    for mode in chosen:
        first = next(r for r in report if r["mode"] == mode)
        if mode == "tf2d":
            verdict = "met" if first["median_ms"] <= TF2D_TARGET_MS else "not met"
            print(f"  tf2d      {first['median_ms']:8.1f} ms/frame   target <= {TF2D_TARGET_MS:.0f} ms: {verdict}")
        else:
            verdict = "met" if first["ratio"] <= TARGETS[mode] else "not met"
            print(f"  {mode:9s} {first['ratio']:8.2f} x VTK      target <= {TARGETS[mode]:.2f}: {verdict}")
    print(f"gl: {gl}")
    print(f"images: {args.out}/side_by_side_<mode>.png (VTK left, voxlab right)")
    if args.json:
        print(json.dumps({"size": args.size, "step": args.step, "frames": args.frames, "results": report}, indent=2))


if __name__ == "__main__":
    main()
