#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Render an igac run with ParaView: the deformed body coloured by stress.

    /usr/bin/python3 scripts/render_paraview.py OUT/solution.pvd OUT/body.png \
        [--field von_mises|stress_magnitude] [--scale S] [--size 1000]

writes OUT/body.png (the whole body at the last load step, Warp By Vector
with the displacement, coloured by the field) and, when the run has a contact
face, OUT/body_zoom.png (the same around the contact zone, with the contact
pressure along the face; the first contact's zone when there are several).  The cells are VTK's rational Bezier cells, so
ParaView draws the exact geometry; --scale magnifies the displacement (by
default 1 when it is visible, otherwise enough to make it about 5 % of the
body's size, and the picture says so).

How ParaView is found.  The script needs pvbatch and ParaView's Python
modules (Debian: paraview and python3-paraview).  Debian's python3-paraview
conflicts with python3-vtk9, which libvtk9-dev (igac's build dependency)
needs, so installing it would remove the VTK headers.  When the modules are
not installed, the script unpacks the python3-paraview package into a cache
folder (apt-get download + dpkg-deb -x, no installation) and points pvbatch's
PYTHONPATH at it.  Rendering is offscreen; if pvbatch cannot open an
offscreen context it runs under xvfb-run.
"""
import argparse
import glob
import os
import random
import shutil
import subprocess
import sys
import tempfile

CACHE = os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "igac", "python3-paraview")


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pvd")
    ap.add_argument("png")
    ap.add_argument("--field", default="von_mises")
    ap.add_argument("--scale", type=float, default=None, help="displacement magnification")
    ap.add_argument("--size", type=int, default=1000, help="image width and height in pixels")
    return ap.parse_args(argv)


# ----------------------------------------------------------------- launcher

def paraview_modules():
    """Folder holding paraview/ and vtkmodules/ for pvbatch, or None."""
    for d in ["/usr/lib/python3/dist-packages", os.path.join(CACHE, "usr/lib/python3/dist-packages")]:
        if os.path.isfile(os.path.join(d, "paraview", "simple.py")):
            return d
    return None


def unpack_python3_paraview():
    if not shutil.which("apt-get") or not shutil.which("dpkg-deb"):
        return None
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run(["apt-get", "download", "python3-paraview"], cwd=tmp, capture_output=True, text=True)
        debs = glob.glob(os.path.join(tmp, "python3-paraview_*.deb"))
        if r.returncode != 0 or not debs:
            sys.stderr.write(f"render_paraview: apt-get download python3-paraview failed: {r.stderr.strip()}\n")
            return None
        os.makedirs(CACHE, exist_ok=True)
        subprocess.run(["dpkg-deb", "-x", debs[0], CACHE], check=True)
    return paraview_modules()


def launch(argv):
    pvbatch = shutil.which("pvbatch")
    if not pvbatch:
        sys.exit("render_paraview: pvbatch not found (Debian: apt-get install paraview)")
    modules = paraview_modules() or unpack_python3_paraview()
    if not modules:
        sys.exit("render_paraview: ParaView's Python modules not found (Debian package python3-paraview)")
    env = dict(os.environ)
    env["PYTHONPATH"] = modules + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    script = os.path.abspath(__file__)
    cmd = [pvbatch, "--force-offscreen-rendering", script] + argv
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    # pvbatch built for X without an offscreen (EGL / OSMesa) context: a
    # virtual X server, at a random display number so that concurrent runs
    # do not race for the same one, retried a few times.
    for attempt in range(4):
        if r.returncode == 0 or not shutil.which("xvfb-run"):
            break
        n = str(random.randint(100, 30000))
        r = subprocess.run(["xvfb-run", "-a", "-n", n, "-s", "-screen 0 1280x1024x24", pvbatch, script] + argv,
                           env=env, capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    if r.returncode != 0:
        sys.stderr.write(r.stderr[-4000:])
        sys.exit(f"render_paraview: pvbatch failed (exit {r.returncode})")


# ----------------------------------------------------------------- rendering

def nice(x):
    """1, 2 or 5 times a power of ten, at most x."""
    import math
    e = math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * 10 ** e <= x:
            return m * 10 ** e
    return 10 ** e


def render(args):
    import math

    from paraview import servermanager as sm
    from paraview.simple import (ColorBy, ExtractBlock, GetActiveViewOrCreate, GetColorTransferFunction,
                                 GetScalarBar, Hide, PVDReader, SaveScreenshot, Show, Text, WarpByVector)

    reader = PVDReader(FileName=os.path.abspath(args.pvd))
    times = list(reader.TimestepValues) if reader.TimestepValues else [None]
    if not isinstance(times, list):
        times = [times]
    t = times[-1]
    view = GetActiveViewOrCreate("RenderView")
    if t is not None:
        view.ViewTime = t
    reader.UpdatePipeline(t) if t is not None else reader.UpdatePipeline()
    data = sm.Fetch(reader)
    # Several parts (body, contact face, multipliers) make a multiblock; a
    # run without contact has the body alone.
    names = ([data.GetMetaData(i).Get(data.NAME()) for i in range(data.GetNumberOfBlocks())]
             if data.IsA("vtkMultiBlockDataSet") else [])

    def block(name):
        return ExtractBlock(Input=reader, Selectors=[f"/Root/{name}"])

    body = block("body") if "body" in names else reader
    body.UpdatePipeline(t) if t is not None else body.UpdatePipeline()
    info = body.GetDataInformation()
    b = info.GetBounds()
    diag = math.sqrt(sum((b[2 * i + 1] - b[2 * i]) ** 2 for i in range(3)))
    umax = info.GetPointDataInformation().GetArrayInformation("displacement").GetComponentRange(-1)[1]
    three_d = (b[5] - b[4]) > 1e-12 * diag
    scale = args.scale
    if scale is None:
        scale = 1.0 if umax >= 0.02 * diag or umax == 0 else nice(0.05 * diag / umax)

    warp = WarpByVector(Input=body, Vectors=["POINTS", "displacement"], ScaleFactor=scale)
    view.ViewSize = [args.size, args.size]
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 0
    disp = Show(warp, view)
    disp.NonlinearSubdivisionLevel = 3  # tessellate the Bezier cells finely
    ColorBy(disp, ("POINTS", args.field))
    lut = GetColorTransferFunction(args.field)
    lut.ApplyPreset("Turbo", True) if hasattr(lut, "ApplyPreset") else None
    disp.RescaleTransferFunctionToDataRange(True, False)
    lo, hi = lut.RGBPoints[0], lut.RGBPoints[-4]
    if hi - lo <= 1e-9 * max(abs(lo), abs(hi), 1e-300):  # a constant field (patch test)
        lut.RescaleTransferFunction(lo - 0.01 * abs(lo) - 1e-12, hi + 0.01 * abs(hi) + 1e-12)
    disp.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = args.field.replace("_", " ")
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]

    label = os.path.basename(os.path.dirname(os.path.abspath(args.pvd)))
    caption = f"{label}: deformed body"
    caption += f", displacement x {scale:g}" if scale != 1 else ""
    caption += f", load factor {t:g}" if t is not None else ""
    text = Text(Text=caption)
    tdisp = Show(text, view)
    tdisp.Color = [0, 0, 0]
    tdisp.FontSize = 14
    tdisp.WindowLocation = "Upper Center"

    cx, cy, cz = (b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2
    if three_d:
        # igac's 3D models are octants x, y >= 0: look at the symmetry planes
        # x = 0 and y = 0, where the interior stress shows.
        view.CameraPosition = [cx - 1.8 * diag, cy - 2.4 * diag, cz + 1.2 * diag]
        view.CameraViewUp = [0, 0, 1]
    else:
        view.CameraPosition = [cx, cy, cz + 3 * diag]
        view.CameraViewUp = [0, 1, 0]
        view.CameraParallelProjection = 1
    view.CameraFocalPoint = [cx, cy, cz]
    view.ResetCamera()
    SaveScreenshot(args.png, view, ImageResolution=[args.size, args.size])
    print(f"render_paraview: wrote {args.png}")

    # Zoom on the contact zone: the extent of the active multipliers (of the
    # first contact when there are several: parts contact_face_<face>, ...).
    face_part = next((n for n in names if n.startswith("contact_face")), None)
    mult_part = next((n for n in names if n.startswith("multipliers")), None)
    if face_part and mult_part:
        mult = sm.Fetch(block(mult_part))
        pts = None
        it = mult.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            pts = it.GetCurrentDataObject()
            it.GoToNextItem()
        active = pts.GetPointData().GetArray("active") if pts else None
        xs = [pts.GetPoint(i) for i in range(pts.GetNumberOfPoints()) if active and active.GetValue(i) > 0.5] if pts else []
        if xs:
            lo = [min(p[k] for p in xs) for k in range(3)]
            hi = [max(p[k] for p in xs) for k in range(3)]
            centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
            extent = max(max(hi[k] - lo[k] for k in range(3)), 1e-3 * diag)
            face = WarpByVector(Input=block(face_part), Vectors=["POINTS", "displacement"], ScaleFactor=scale)
            fdisp = Show(face, view)
            fdisp.NonlinearSubdivisionLevel = 3
            fdisp.LineWidth = 7.0
            fdisp.RenderLinesAsTubes = 1
            if not three_d:
                fdisp.Position = [0, 0, 1e-3 * diag]  # in front of the body's boundary
            ColorBy(fdisp, ("POINTS", "pressure"))
            plut = GetColorTransferFunction("pressure")
            fdisp.RescaleTransferFunctionToDataRange(True, False)
            fdisp.SetScalarBarVisibility(view, True)
            pbar = GetScalarBar(plut, view)
            pbar.Title = "contact pressure"
            pbar.TitleColor = pbar.LabelColor = [0, 0, 0]
            pbar.WindowLocation = "Upper Right Corner"
            text.Text = caption + " (contact zone)"
            if three_d:
                # from outside the symmetry planes, slightly below the contact face
                c3 = [centre[0] + 0.3 * extent, centre[1] + 0.3 * extent, centre[2] + 0.5 * extent]
                view.CameraFocalPoint = c3
                view.CameraPosition = [c3[0] - 2.2 * extent, c3[1] - 2.9 * extent, c3[2] - 0.6 * extent]
                view.CameraViewUp = [0, 0, 1]
                view.CameraParallelProjection = 0
                view.CameraViewAngle = 30
            else:
                view.CameraFocalPoint = [centre[0] + 0.3 * extent, centre[1] + 0.7 * extent, 0]
                view.CameraPosition = [centre[0] + 0.3 * extent, centre[1] + 0.7 * extent, 3 * diag]
                view.CameraParallelScale = 1.1 * extent
            root, ext = os.path.splitext(args.png)
            SaveScreenshot(root + "_zoom" + ext, view, ImageResolution=[args.size, args.size])
            print(f"render_paraview: wrote {root}_zoom{ext}")
            Hide(face, view)


def main(argv):
    args = parse(argv)
    try:
        import paraview.simple  # noqa: F401  (inside pvbatch)
    except ImportError:
        launch(argv)
        return
    render(args)


if __name__ == "__main__":
    main(sys.argv[1:])
