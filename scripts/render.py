"""Renders an fecontact output file with ParaView (pvbatch): the bodies coloured by a field, the
contact forces of the frame's step as arrows (ParaView's Glyph filter on the XDMF grid
"contact-points": length proportional to |force|, pointing along the force on side 1 and ending on
the contact point, as if pushing on body 1).

  xvfb-run -a pvbatch scripts/render.py out/default.xmf -o out/default_scene.png
  xvfb-run -a pvbatch scripts/render.py out/grasp_rotate.h5 --field von_mises --time 0.3 -o grasp.png
  xvfb-run -a pvbatch scripts/render.py out/default.xmf --all-frames -o frames/default.png   # frames/default_0000.png ...

FILE is the .xmf (or the .h5 beside it). --field: a point field (displacement, velocity: coloured by
magnitude) or a cell field (von_mises, energy_density) of the run's -output_fields; bodies without it
are grey. --time: the frame at or before this time (default: the last). --all-frames: one PNG per
frame (a movie: ffmpeg -i frames/default_%04d.png movie.mp4). --view iso|x|y|z, --size WxH,
--arrow-length: the longest arrow as a fraction of the scene's size (default 0.25, the same scale in
every frame of a run). xvfb-run gives pvbatch a display on a machine without one."""
import argparse
import os
import sys

from paraview import servermanager
from paraview.simple import (Calculator, ColorBy, CreateView, ExtractBlock, GetColorTransferFunction, Glyph, Render,
                             SaveScreenshot, Show, XDMFReader)

CELL_FIELDS = ("von_mises", "energy_density")
TITLES = {"displacement": "|displacement| (m)", "velocity": "|velocity| (m/s)", "von_mises": "von Mises stress (Pa)",
          "energy_density": "energy density (J/m^3)"}

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("file", help="the run's .xmf (or its .h5)")
ap.add_argument("-o", "--output", default=None, help="PNG to write (default: FILE with .png)")
ap.add_argument("--field", default="velocity", help="field to colour the bodies by (default velocity)")
ap.add_argument("--time", type=float, default=None, help="time (s); default: the last frame")
ap.add_argument("--all-frames", action="store_true", help="one PNG per frame: OUTPUT_0000.png, ...")
ap.add_argument("--view", default="iso", choices=["iso", "x", "y", "z"], help="camera direction (default iso)")
ap.add_argument("--size", default="1280x800", help="image size WxH (default 1280x800)")
ap.add_argument("--opacity", type=float, default=None,
                help="opacity of the bodies (default 0.5 with contacts, so that the arrows show through the bodies that "
                     "press, 1 without)")
ap.add_argument("--arrow-length", type=float, default=0.25, help="longest arrow / scene size (default 0.25)")
a = ap.parse_args()

xmf = os.path.abspath(a.file[:-3] + ".xmf" if a.file.endswith(".h5") else a.file)
if not os.path.exists(xmf):
    sys.exit("render.py: no such file %s" % xmf)
png = a.output or os.path.splitext(a.file)[0] + ".png"
W, H = (int(v) for v in a.size.split("x"))

reader = XDMFReader(FileNames=[xmf])  # keeps the grids as named blocks
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) or [0.0]
data = servermanager.Fetch(reader)
names = [data.GetMetaData(i).Get(data.NAME()) for i in range(data.GetNumberOfBlocks())] \
    if data.IsA("vtkMultiBlockDataSet") else ["body"]
bodies = [n for n in names if n != "contact-points"]
has_contacts = "contact-points" in names

view = CreateView("RenderView")
view.ViewSize = [W, H]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
view.Background = [1, 1, 1]
view.OrientationAxesVisibility = 0
if data.IsA("vtkMultiBlockDataSet"):
    src = ExtractBlock(Input=reader, Selectors=["/Root/%s" % n for n in bodies])
else:
    src = reader
shown = Show(src, view)
where = "CELLS" if a.field in CELL_FIELDS else "POINTS"
ColorBy(shown, (where, a.field, "Magnitude") if where == "POINTS" else (where, a.field))
lut = GetColorTransferFunction(a.field)
lut.NanColor = [0.75, 0.75, 0.75]
shown.SetScalarBarVisibility(view, True)
bar = lut.GetScalarBar(view) if hasattr(lut, "GetScalarBar") else None
try:
    from paraview.simple import GetScalarBar
    bar = GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = TITLES.get(a.field, a.field), ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
except Exception:
    pass


def bounds_and_forces(t):
    """scene bounds and largest contact force at time t"""
    src.UpdatePipeline(t)
    b = src.GetDataInformation().GetBounds()
    fmax = 0.0
    if has_contacts:
        contacts.UpdatePipeline(t)
        info = contacts.GetDataInformation().GetPointDataInformation().GetArrayInformation("force_world")
        if info is not None:
            fmax = info.GetComponentRange(-1)[1]
    return b, fmax


contacts = None
if has_contacts:
    # ParaView's block selectors drop the characters of a name other than letters, digits and '_'
    contacts = ExtractBlock(Input=reader, Selectors=["/Root/contactpoints"])
    # each arrow ends on its contact point (it pushes on body 1): drawn from p - s F to p
    tails = Calculator(Input=contacts, CoordinateResults=1, ResultArrayName="tail", Function="coords")
    arrows = Glyph(Input=tails, GlyphType="Arrow")
    arrows.OrientationArray = ["POINTS", "force_world"]
    arrows.ScaleArray = ["POINTS", "force_world"]
    arrows.GlyphMode = "All Points"
    ashown = Show(arrows, view)
    ashown.ColorArrayName = ["POINTS", ""]
    ashown.AmbientColor = ashown.DiffuseColor = [0.85, 0.1, 0.1]
shown.Opacity = a.opacity if a.opacity is not None else (0.5 if has_contacts else 1.0)

frames = range(len(times)) if a.all_frames else [max(i for i, t in enumerate(times) if a.time is None or t <= a.time + 1e-12)]
# one colour range and one arrow scale for all the frames drawn
size, fmax, lo, hi = 0.0, 0.0, float("inf"), -float("inf")
for i in frames:
    b, f = bounds_and_forces(times[i])
    size = max(size, ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5)
    fmax = max(fmax, f)
    info = src.GetDataInformation()
    arr = (info.GetCellDataInformation() if where == "CELLS" else info.GetPointDataInformation()).GetArrayInformation(a.field)
    if arr is not None:
        r = arr.GetComponentRange(-1)
        lo, hi = min(lo, r[0]), max(hi, r[1])
if lo > hi:
    print("render.py: no body has the field '%s' (see -output_fields)" % a.field)
    lo, hi = 0.0, 1.0
lut.RescaleTransferFunction(lo, hi if hi > lo else lo + 1e-30)
if has_contacts:
    arrows.ScaleFactor = a.arrow_length * size / fmax if fmax > 0 else 0.0
    tails.Function = "coords - %.17g * force_world" % arrows.ScaleFactor

view.ResetCamera()
cam = view.GetActiveCamera()
direction = {"iso": (1, -1.4, 0.9), "x": (1, 0, 0), "y": (0, -1, 0), "z": (0, 0, 1)}[a.view]
view.CameraFocalPoint = list(cam.GetFocalPoint())
view.CameraPosition = [view.CameraFocalPoint[k] + direction[k] for k in range(3)]
view.CameraViewUp = [0, 1, 0] if a.view == "z" else [0, 0, 1]
view.ResetCamera()
cam.Zoom(1.3)
for i in frames:
    view.ViewTime = times[i]
    Render(view)
    name = "%s_%04d.png" % (os.path.splitext(png)[0], i) if a.all_frames else png
    if os.path.dirname(name):
        os.makedirs(os.path.dirname(name), exist_ok=True)
    SaveScreenshot(name, view, ImageResolution=[W, H])
    print("render.py: %s (t = %g s, %s)" % (name, times[i], a.field))
