"""Render a result of bin/signorini with ParaView: the deformed body coloured by a field, to a PNG, without a display.

    xvfb-run -a pvpython scripts/render.py RESULT.xmf OUT.png [--field von_mises] [--scale 20] [--step last]
                                           [--size 1200 600] [--list]

RESULT.xmf is the XDMF file written beside -output_file RESULT.h5 (any name: spaces, dots, other directories).
--field      a vertex field (displacement, contact_pressure, gap, penetration, active, obstacle_offset, with
             friction tangential_traction, slip, friction_state, with two bodies master_pressure) or a cell field
             (von_mises, shear_energy_density, with two bodies body);
             a vector field is coloured by its magnitude (default: von_mises)
--scale      the displacement magnification of the picture (default: the one stored in the file,
             -output_magnification, 20 unless given; 0 draws the undeformed body)
--step       with load steps (a temporal collection): the step to draw, 1 to N or "last" (default)
--list       print the fields of the file and exit
Exit status 0 when the picture was written, 1 on a bad argument (an unknown field names the ones there are).
Needs ParaView's Python (Debian: apt-get install paraview python3-paraview xvfb); documented in doc/paraview.md.
"""
import argparse
import os
import re
import sys


def stored_magnification(xmf):
    """-output_magnification as written into the .xmf (<Information Name="magnification" Value=...>)."""
    with open(xmf, encoding="utf-8", errors="replace") as f:
        m = re.search(r'<Information Name="magnification" Value="([^"]+)"', f.read())
    return float(m.group(1)) if m else 20.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("xmf")
    ap.add_argument("png", nargs="?")
    ap.add_argument("--field", default="von_mises")
    ap.add_argument("--scale", type=float, default=None)
    ap.add_argument("--step", default="last")
    ap.add_argument("--size", type=int, nargs=2, default=[1200, 600])
    ap.add_argument("--list", action="store_true")
    opt = ap.parse_args()
    if not os.path.isfile(opt.xmf):
        print("render.py: %s: no such file" % opt.xmf)
        return 1
    if not opt.list and not opt.png:
        print("render.py: give the output picture (OUT.png) or --list")
        return 1

    from paraview import simple as pv  # noqa: E402 (pvpython only: --help works without ParaView)

    reader = pv.XDMFReader(FileNames=[os.path.abspath(opt.xmf)])
    reader.UpdatePipelineInformation()
    tv = reader.TimestepValues  # a load-step collection: its load factors (one float for a single step)
    times = [float(tv)] if isinstance(tv, (int, float)) else [float(x) for x in tv] if tv else []
    t = None
    if times:
        if opt.step == "last":
            t = times[-1]
        else:
            k = int(opt.step)
            if not 1 <= k <= len(times):
                print("render.py: --step %s: the file has load steps 1 to %d" % (opt.step, len(times)))
                return 1
            t = times[k - 1]
    reader.UpdatePipeline(t) if t is not None else reader.UpdatePipeline()
    info = reader.GetDataInformation()
    points = [reader.PointData[i].Name for i in range(len(reader.PointData))]
    cells = [reader.CellData[i].Name for i in range(len(reader.CellData))]
    if opt.list:
        print("vertex fields: %s" % ", ".join(points))
        print("cell fields: %s" % ", ".join(cells))
        print("load steps: %s" % (", ".join("%g" % x for x in times) if times else "none"))
        return 0
    if not points and not cells and ":" in os.path.basename(opt.xmf):
        print("render.py: %s: ParaView read no fields: its XDMF reader cuts the HDF5 reference FILE:/dataset at the "
              "first ':', and this file name has one; rename the .h5 and .xmf without ':' (and the reference inside "
              "the .xmf)" % opt.xmf)
        return 1
    if opt.field in points:
        assoc = "POINTS"
    elif opt.field in cells:
        assoc = "CELLS"
    else:
        print("render.py: --field %s: not in %s; its fields: %s" % (opt.field, opt.xmf, ", ".join(points + cells)))
        return 1
    if "displacement" not in points:
        print("render.py: %s has no displacement field" % opt.xmf)
        return 1

    scale = stored_magnification(opt.xmf) if opt.scale is None else opt.scale
    bounds = info.GetBounds()
    dim3 = bounds[5] - bounds[4] > 1e-12 * max(1.0, bounds[1] - bounds[0])
    warp = pv.WarpByVector(Input=reader)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = scale
    view = pv.CreateView("RenderView")
    view.ViewSize = list(opt.size)
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 0
    if t is not None:
        view.ViewTime = t
    disp = pv.Show(warp, view)
    disp.SetRepresentationType("Surface With Edges" if info.GetNumberOfCells() <= 20000 else "Surface")
    pv.ColorBy(disp, (assoc, opt.field, "Magnitude"))
    disp.RescaleTransferFunctionToDataRange(True, False)
    disp.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(pv.GetColorTransferFunction(opt.field), view)
    bar.Title = opt.field
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    if dim3:
        view.CameraPosition = [1, -1.5, 1]
        view.CameraViewUp = [0, 0, 1]
    else:
        view.CameraPosition = [0, 0, 1]
        view.CameraViewUp = [0, 1, 0]
        view.InteractionMode = "2D"
    view.CameraFocalPoint = [0, 0, 0]
    view.ResetCamera()
    pv.Render(view)
    pv.SaveScreenshot(opt.png, view, ImageResolution=list(opt.size))
    ok = os.path.isfile(opt.png) and os.path.getsize(opt.png) > 0
    rng = reader.PointData[opt.field].GetRange(-1) if assoc == "POINTS" else reader.CellData[opt.field].GetRange(-1)
    print("render.py: %s: %s (%s), range %.6g to %.6g, displacement x%g%s -> %s" % (
        opt.xmf, opt.field, "vertex" if assoc == "POINTS" else "cell", rng[0], rng[1], scale,
        ", load factor %g" % t if t is not None else "", opt.png if ok else "NOT WRITTEN"))
    return 0 if ok else 1


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    # leave without ParaView's teardown: under Xvfb it can fail on the GL context after the picture is written
    # (GLXBadContext), which would turn a good run into a failed one
    os._exit(code)
