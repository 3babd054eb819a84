#!/usr/bin/env python3
"""Render a voxcast scene with VTK's vtkFixedPointVolumeRayCastMapper and time it.

The peer of voxcast's ray caster (docs/performance.md, "Against the peer"):
the same volume, transfer function, camera, image size, sample distance,
shading coefficients and lights as the scene, 15-bit fixed point in VTK.

    xvfb-run -a python3 bench/vtk_peer.py scenes/colin27.toml --frames 10 --png vtk.png

prints one JSON object on stdout: ms per frame (median, min, every frame),
the VTK version, the threads the mapper used, and what was matched. Without
a display it re-runs itself under `xvfb-run -a`. Every failure is one line
on stderr, `vtk_peer: WHAT`, and exit status 1 (2 for VTK or Xvfb missing).

Only the subset of scene keys the peer can express is read: a NIfTI-1
volume (u8, i16, u16), `ramp`/`binary` classification, ka/kd/ks/shininess,
the camera (perspective or parallel), render.width/height/oversampling/
background/mode (`shaded` or `unshaded`), and headlight/directional lights.
Anything else in the scene is ignored and listed under "ignored" in the JSON.
"""

import argparse
import gzip
import json
import os
import shutil
import statistics
import struct
import sys
import time

MISSING_STATUS = 2
INSTALL_HINT = "apt-get install -y python3-vtk9 xvfb xauth"


def fail(msg, status=1):
    print(f"vtk_peer: {msg}", file=sys.stderr)
    sys.exit(status)


# ---------------------------------------------------------------- the scene

def load_toml(path):
    try:
        import tomllib  # Python 3.11 (Debian 12's python3)
    except ImportError:
        try:
            import tomli as tomllib  # older Pythons with python3-tomli
        except ImportError:
            fail("reading a scene needs Python >= 3.11 (tomllib) or python3-tomli")
    try:
        with open(path, "rb") as f:
            return tomllib.load(f)
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    except tomllib.TOMLDecodeError as e:
        fail(f"{path}: {e}")


NIFTI_TYPES = {2: ("B", 1, "unsigned_char"), 4: ("h", 2, "short"), 512: ("H", 2, "unsigned_short")}


def load_nifti(path):
    """The voxels in file order (x fastest), as voxcast reads them: the
    orientation (qform/sform) is not applied (docs/volumes.md)."""
    try:
        opener = gzip.open if path.endswith(".gz") else open
        with opener(path, "rb") as f:
            data = f.read()
    except (OSError, EOFError) as e:
        fail(f"{path}: cannot read ({e})")
    if len(data) < 352:
        fail(f"{path}: not a NIfTI-1 file (too short)")
    for endian in "<>":
        if struct.unpack(endian + "i", data[0:4])[0] == 348:
            break
    else:
        fail(f"{path}: not a NIfTI-1 file (sizeof_hdr is not 348)")
    dim = struct.unpack(endian + "8h", data[40:56])
    datatype = struct.unpack(endian + "h", data[70:72])[0]
    pixdim = struct.unpack(endian + "8f", data[76:108])
    vox_offset = int(struct.unpack(endian + "f", data[108:112])[0])
    slope, inter = struct.unpack(endian + "2f", data[112:120])
    if dim[0] < 3 or any(d < 1 for d in dim[1:4]) or any(d > 1 for d in dim[4:1 + dim[0]]):
        fail(f"{path}: only single 3-D volumes are supported (dim = {dim[:1 + dim[0]]})")
    if datatype not in NIFTI_TYPES:
        fail(f"{path}: NIfTI datatype {datatype} not supported here (u8, i16, u16)")
    fmt, size, vtk_type = NIFTI_TYPES[datatype]
    dims = dim[1:4]
    n = dims[0] * dims[1] * dims[2]
    raw = data[vox_offset:vox_offset + n * size]
    if len(raw) != n * size:
        fail(f"{path}: truncated data ({len(raw)} of {n * size} bytes)")
    if size > 1 and endian != ("<" if sys.byteorder == "little" else ">"):
        raw = struct.pack("=" + fmt * n, *struct.unpack(endian + fmt * n, raw))
    if slope == 0.0:
        slope, inter = 1.0, 0.0
    spacing = [abs(p) if p else 1.0 for p in pixdim[1:4]]
    return {"dims": dims, "raw": raw, "vtk_type": vtk_type, "spacing": spacing,
            "slope": slope, "inter": inter}


def scene_source(scene, scene_path):
    src = scene.get("volume", {}).get("source", "phantom:shepp-logan")
    if src.startswith("phantom:"):
        fail(f"volume.source = \"{src}\": the peer reads NIfTI files only")
    if not os.path.isabs(src):
        src = os.path.join(os.path.dirname(os.path.abspath(scene_path)), src)
    if not (src.endswith(".nii") or src.endswith(".nii.gz")):
        fail(f"volume.source = \"{src}\": the peer reads NIfTI files only")
    return src


def parse_value(text):
    """A --set value read as TOML (4, [1, 2, 3], "ramp"), else a bare string,
    as voxcast's --set does (docs/scenes.md)."""
    try:
        import tomllib
    except ImportError:
        import tomli as tomllib
    try:
        return tomllib.loads("v = " + text)["v"]
    except Exception:
        return text


def apply_set(scene, assignment):
    """`--set render.width=64`, `--set 'lights[0].intensity=0.5'`."""
    import re
    key, sep, value = assignment.partition("=")
    if not sep or not key:
        fail(f"--set {assignment}: expected KEY=VALUE")
    parts = []
    for name in key.split("."):
        m = re.fullmatch(r"([A-Za-z_][A-Za-z0-9_]*)(?:\[(\d+)\])?", name)
        if m:
            parts.append(m.group(1))
            if m.group(2) is not None:
                parts.append(int(m.group(2)))
        elif name.isdigit():
            parts.append(int(name))
        else:
            fail(f"--set {assignment}: cannot read the key")
    node = scene
    for i, part in enumerate(parts[:-1]):
        nxt = [] if isinstance(parts[i + 1], int) else {}
        if isinstance(part, int):
            if not isinstance(node, list) or part > len(node):
                fail(f"--set {assignment}: no element {part}")
            if part == len(node):
                node.append(nxt)
            node = node[part]
        else:
            node = node.setdefault(part, nxt)
    last = parts[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or last > len(node):
            fail(f"--set {assignment}: no element {last}")
        if last == len(node):
            node.append(None)
    node[last] = parse_value(value)


# ---------------------------------------------------------------- VTK

def import_vtk():
    try:
        import vtkmodules.all as vtk  # noqa: F401  (the whole VTK, as `import vtk`)
    except ImportError:
        print(f"vtk_peer: python3 cannot import vtk: install it with `{INSTALL_HINT}`",
              file=sys.stderr)
        sys.exit(MISSING_STATUS)
    return vtk


def build_pipeline(vtk, scene, vol, args, ignored):
    cls = scene.get("classification", {})
    cam = scene.get("camera", {})
    ren_desc = scene.get("render", {})
    width = int(ren_desc.get("width", 256))
    height = int(ren_desc.get("height", 256))
    oversampling = float(ren_desc.get("oversampling", 1.0))
    mode = ren_desc.get("mode", "shaded")
    if mode not in ("shaded", "unshaded"):
        fail(f"render.mode = \"{mode}\": the peer is timed in compositing modes only")
    if ren_desc.get("algorithm", "raycast") != "raycast":
        fail("render.algorithm: the peer is a ray caster")
    for key in ("jitter", "partial_segments", "ert_threshold", "space_leaping", "leap_block",
                "frames", "threads"):
        if key in ren_desc:
            ignored.append(f"render.{key}")
    for key in ("crop", "gradient"):
        if key in scene.get("volume", {}):
            ignored.append(f"volume.{key}")
    for key in ("precision", "rtl", "heidelberg"):
        if key in scene:
            ignored.append(f"[{key}]")

    # World space as voxcast's: voxel coordinates scaled by spacing / smallest spacing.
    smallest = min(vol["spacing"])
    world_scale = [s / smallest for s in vol["spacing"]]

    importer = vtk.vtkImageImport()
    importer.CopyImportVoidPointer(vol["raw"], len(vol["raw"]))
    getattr(importer, "SetDataScalarTypeTo" + {"unsigned_char": "UnsignedChar", "short": "Short",
                                               "unsigned_short": "UnsignedShort"}[vol["vtk_type"]])()
    importer.SetNumberOfScalarComponents(1)
    d = vol["dims"]
    importer.SetDataExtent(0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1)
    importer.SetWholeExtent(0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1)
    importer.SetDataSpacing(*world_scale)
    importer.SetDataOrigin(0.0, 0.0, 0.0)
    importer.Update()

    # Transfer function: the points are in the data's physical unit; VTK's
    # tables are indexed by the stored value.
    points = cls.get("points", [])
    if not points:
        fail("classification.points: at least one point is needed")
    interp = cls.get("interpolation", "ramp")
    if interp not in ("ramp", "binary"):
        fail(f"classification.interpolation = \"{interp}\" is not ramp or binary")
    stored = [((float(p["value"]) - vol["inter"]) / vol["slope"],
               [float(c) for c in p.get("color", [1.0, 1.0, 1.0])],
               float(p.get("alpha", 0.0))) for p in points]
    if vol["slope"] < 0:
        stored.reverse()
    lo = min(s[0] for s in stored)
    hi = max(s[0] for s in stored)
    eps = max(hi - lo, 1.0) * 1e-6
    tf_points = []  # (x, rgb, alpha), strictly increasing x
    for i, (x, rgb, a) in enumerate(stored):
        if interp == "binary" and i > 0:
            # a zero-order hold: the previous point's values up to just below x
            tf_points.append((x - eps, stored[i - 1][1], stored[i - 1][2]))
        tf_points.append((x, rgb, a))
    fixed = []
    for x, rgb, a in tf_points:  # equal values (a vertical step) must stay distinct in VTK
        if fixed and x <= fixed[-1][0]:
            x = fixed[-1][0] + eps
        fixed.append((x, rgb, a))
    color = vtk.vtkColorTransferFunction()
    opacity = vtk.vtkPiecewiseFunction()
    for x, rgb, a in fixed:
        color.AddRGBPoint(x, *rgb)
        opacity.AddPoint(x, a)
    color.ClampingOn()
    opacity.ClampingOn()

    # Lights: voxcast's are at infinity (directional); a headlight shines
    # along the view. A scene without lights has one headlight of intensity 1.
    lights = scene.get("lights", [{"type": "headlight", "intensity": 1.0}])
    vtk_lights = []
    total_intensity = 0.0
    for i, l in enumerate(lights):
        light = vtk.vtkLight()
        light.SetAmbientColor(1.0, 1.0, 1.0)
        light.SetDiffuseColor(1.0, 1.0, 1.0)
        light.SetSpecularColor(1.0, 1.0, 1.0)
        intensity = float(l.get("intensity", 1.0))
        light.SetIntensity(intensity)
        light.PositionalOff()
        kind = l.get("type", "headlight")
        if kind == "headlight":
            light.SetLightTypeToHeadlight()
        elif kind == "directional":
            light.SetLightTypeToSceneLight()
            # direction towards the light, in world axes: VTK's light shines
            # from its position to its focal point
            light.SetPosition(*[float(c) for c in l["direction"]])
            light.SetFocalPoint(0.0, 0.0, 0.0)
        else:
            fail(f"lights[{i}].type = \"{kind}\" is not headlight or directional")
        total_intensity += intensity
        vtk_lights.append(light)

    ka = float(cls.get("ka", 0.1))
    kd = float(cls.get("kd", 0.7))
    ks = float(cls.get("ks", 0.2))
    shininess = float(cls.get("shininess", 20.0))
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    # voxcast's alpha is the opacity of one world unit (one voxel of the
    # smallest spacing) of path, corrected to 1-(1-alpha)^step: VTK's
    # scalar opacity unit distance is exactly that unit.
    prop.SetScalarOpacityUnitDistance(1.0)
    prop.DisableGradientOpacityOn()
    prop.SetInterpolationTypeToLinear()
    prop.SetShade(1 if mode == "shaded" else 0)
    # VTK adds ka * intensity once per light (vtkEncodedGradientShader);
    # voxcast adds ka once: divide by the lights' total intensity.
    prop.SetAmbient(ka / total_intensity if total_intensity > 0 else 0.0)
    prop.SetDiffuse(kd)
    prop.SetSpecular(ks)
    prop.SetSpecularPower(shininess)

    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputConnection(importer.GetOutputPort())
    mapper.SetBlendModeToComposite()
    mapper.AutoAdjustSampleDistancesOff()
    mapper.LockSampleDistanceToInputSpacingOff()
    step = 1.0 / oversampling  # voxcast: samples per world unit
    mapper.SetSampleDistance(step)
    mapper.SetInteractiveSampleDistance(step)
    mapper.SetImageSampleDistance(1.0)
    mapper.SetMinimumImageSampleDistance(1.0)
    mapper.SetMaximumImageSampleDistance(1.0)
    mapper.IntermixIntersectingGeometryOff()
    mapper.SetNumberOfThreads(args.threads)

    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtk.vtkRenderer()
    renderer.AutomaticLightCreationOff()
    renderer.RemoveAllLights()
    for light in vtk_lights:
        renderer.AddLight(light)
    renderer.TwoSidedLightingOff()  # voxcast's shading is one-sided
    bg = [float(c) for c in ren_desc.get("background", [0.0, 0.0, 0.0])]
    renderer.SetBackground(*bg)
    renderer.AddVolume(volume)

    camera = renderer.GetActiveCamera()
    if "eye" not in cam or "center" not in cam:
        fail("camera.eye and camera.center are required")
    eye = [float(c) * s for c, s in zip(cam["eye"], world_scale)]
    center = [float(c) * s for c, s in zip(cam["center"], world_scale)]
    dolly = float(cam.get("dolly", 1.0))
    fov = float(cam.get("fov_deg", 40.0))
    if dolly != 1.0:  # docs/scenes.md, camera.dolly
        import math
        eye = [c + (e - c) * dolly for e, c in zip(eye, center)]
        fov = math.degrees(2.0 * math.atan(math.tan(math.radians(fov / 2.0)) / dolly))
    camera.SetPosition(*eye)
    camera.SetFocalPoint(*center)
    camera.SetViewUp(*[float(c) for c in cam.get("up", [0.0, 0.0, 1.0])])
    camera.OrthogonalizeViewUp()
    if cam.get("projection", "perspective") == "parallel":
        camera.ParallelProjectionOn()
        camera.SetParallelScale(float(cam.get("height", 64.0)) / 2.0)
    else:
        camera.ParallelProjectionOff()
        camera.SetViewAngle(fov)  # vertical, as voxcast's fov_deg
    for key in ("stereo_deg", "path"):
        if key in cam:
            ignored.append(f"camera.{key}")
    renderer.ResetCameraClippingRange()

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)

    return {"window": window, "renderer": renderer, "camera": camera, "mapper": mapper,
            "width": width, "height": height, "step": step, "ambient_vtk": prop.GetAmbient(),
            "lights": len(vtk_lights), "world_scale": world_scale}


def write_png(vtk, window, path):
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def png_rgb(vtk, path):
    """(width, height, bytes of RGB rows) of a PNG, read by VTK."""
    reader = vtk.vtkPNGReader()
    if not reader.CanReadFile(path):
        fail(f"{path}: not a readable PNG")
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    w, h, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    n = scalars.GetNumberOfComponents()
    data = bytes(memoryview(scalars))
    if n != 3:
        data = bytes(b for i, b in enumerate(data) if i % n < 3)
    return w, h, data


def compare_images(vtk, ours, theirs):
    """PSNR and mean absolute difference (8-bit RGB) of the VTK image against
    voxcast's, and the share of pixels where only one of them shows the volume."""
    import math
    w, h, a = png_rgb(vtk, ours)
    w2, h2, b = png_rgb(vtk, theirs)
    if (w, h) != (w2, h2):
        fail(f"{theirs}: {w2}x{h2}, the VTK image is {w}x{h}")
    sq = sum((x - y) * (x - y) for x, y in zip(a, b))
    ab = sum(abs(x - y) for x, y in zip(a, b))
    only_one = 0
    for i in range(0, len(a), 3):
        if (a[i] | a[i + 1] | a[i + 2] == 0) != (b[i] | b[i + 1] | b[i + 2] == 0):
            only_one += 1
    mse = sq / len(a)
    return {"against": theirs,
            "psnr_db": round(10 * math.log10(255.0 ** 2 / mse), 2) if mse > 0 else None,
            "mean_abs_diff": round(ab / len(a), 3),
            "coverage_differs": round(only_one / (w * h), 5)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene", help="voxcast scene file (TOML)")
    ap.add_argument("--frames", type=int, default=10, help="timed frames (default 10)")
    ap.add_argument("--warmup", type=int, default=2, help="untimed frames first (default 2)")
    ap.add_argument("--threads", type=int, default=2, help="VTK's ray-casting threads (default 2)")
    ap.add_argument("--png", help="write the image (the last warm-up frame's view) here")
    ap.add_argument("--compare", metavar="PNG",
                    help="with --png: compare the image with this one (voxcast's render)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override a scene key, as voxcast's --set")
    args = ap.parse_args()
    if args.frames < 1 or args.warmup < 1 or args.threads < 1:
        fail("--frames, --warmup and --threads must be at least 1")
    if args.compare and not args.png:
        fail("--compare needs --png")

    import importlib.util
    if importlib.util.find_spec("vtkmodules") is None:
        print(f"vtk_peer: python3 cannot import vtk: install it with `{INSTALL_HINT}`",
              file=sys.stderr)
        sys.exit(MISSING_STATUS)
    if not os.environ.get("DISPLAY") and not os.environ.get("VTK_PEER_NO_XVFB"):
        xvfb = shutil.which("xvfb-run")
        if not xvfb:
            print(f"vtk_peer: no display and no xvfb-run: install it with `{INSTALL_HINT}`",
                  file=sys.stderr)
            sys.exit(MISSING_STATUS)
        os.environ["VTK_PEER_NO_XVFB"] = "1"
        os.execv(xvfb, [xvfb, "-a", sys.executable, os.path.abspath(__file__)] + sys.argv[1:])

    vtk = import_vtk()
    scene = load_toml(args.scene)
    for assignment in args.set:
        apply_set(scene, assignment)
    vol = load_nifti(scene_source(scene, args.scene))
    ignored = []

    vtk.vtkMultiThreader.SetGlobalMaximumNumberOfThreads(args.threads)
    vtk.vtkMultiThreader.SetGlobalDefaultNumberOfThreads(args.threads)
    p = build_pipeline(vtk, scene, vol, args, ignored)
    window, camera, mapper, renderer = p["window"], p["camera"], p["mapper"], p["renderer"]

    # Warm-up: the first render computes VTK's gradients (encoded normals and
    # magnitudes), the min-max volume and the tables; the timed frames do not.
    t0 = time.perf_counter()
    window.Render()
    first_ms = (time.perf_counter() - t0) * 1e3
    for _ in range(args.warmup - 1):
        window.Render()
    if args.png:
        write_png(vtk, window, args.png)

    # Each timed frame moves the camera by a thousandth of a degree about the
    # centre and back on the next, so every frame is a new view (new rays,
    # new shading table) of the same picture.
    wall, mapper_ms = [], []
    sign = 1.0
    for _ in range(args.frames):
        camera.Azimuth(sign * 1e-3)
        sign = -sign
        renderer.ResetCameraClippingRange()
        t0 = time.perf_counter()
        window.Render()
        wall.append((time.perf_counter() - t0) * 1e3)
        mapper_ms.append(mapper.GetTimeToDraw() * 1e3)

    # The mapper's own clock (vtkAbstractMapper::TimeToDraw: the ray cast and
    # drawing its image into the frame) when it reports one, else the wall
    # time of Render() (which adds clearing, the buffer copy, no swap offscreen).
    timed = mapper_ms if all(t > 0 for t in mapper_ms) else wall
    out = {
        "peer": "vtkFixedPointVolumeRayCastMapper",
        "vtk_version": vtk.vtkVersion.GetVTKVersion(),
        "scene": args.scene,
        "threads": mapper.GetNumberOfThreads(),
        "image": [p["width"], p["height"]],
        "frames": args.frames,
        "warmup": args.warmup,
        "clock": "mapper TimeToDraw" if timed is mapper_ms else "Render() wall time",
        "ms_per_frame_median": statistics.median(timed),
        "ms_per_frame_min": min(timed),
        "ms_all": [round(t, 3) for t in timed],
        "wall_ms_median": statistics.median(wall),
        "wall_ms_all": [round(t, 3) for t in wall],
        "first_frame_ms": round(first_ms, 3),
        "sample_distance": p["step"],
        "scalar_opacity_unit_distance": 1.0,
        "space_leaping": "on (VTK's min-max volume of 4x4x4-voxel blocks; no switch)",
        "early_termination": "remaining opacity < 255/32768 (accumulated > 0.9922)",
        "two_sided_lighting": False,
        "ambient_vtk": p["ambient_vtk"],
        "lights": p["lights"],
        "ignored": ignored,
    }
    if args.set:
        out["set"] = args.set
    if args.png:
        out["png"] = args.png
        if args.compare:
            out["compare"] = compare_images(vtk, args.png, args.compare)
    json.dump(out, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
