#!/usr/bin/python3
"""Plots and verdicts of scripts/benchmark.sh, drawn with VTK's charts (run under Xvfb).

  benchmark_report.py accuracy CSV OUTDIR
      One log-log plot per scene of parc-render --accuracy-curve rows (median frame time
      against RMSE to the reference, a line per mapper and image sample distance), written
      to OUTDIR/accuracy-SCENE.png; prints per scene a markdown image link and the verdict:
      which mapper reaches each error fastest.
  benchmark_report.py lines CSV OUT.png TITLE XLABEL YLABEL [--log-x] [--log-y] [--mark-minimum]
      A line per series of a CSV with columns series,x,y; --mark-minimum marks each line's
      smallest y (an optimum) with a large dot.
"""
import csv
import math
import sys
from collections import OrderedDict

from vtkmodules.vtkChartsCore import vtkAxis, vtkChart, vtkChartLegend, vtkChartXY, vtkPlotPoints
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkTable
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingContext2D import vtkPen
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
from vtkmodules.vtkViewsContext2D import vtkContextView
import vtkmodules.vtkRenderingContextOpenGL2  # noqa: F401 (the charts' OpenGL back end)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

# Colours of the series, in order (red, green, blue, 0-255).
PALETTE = [(31, 119, 180), (255, 127, 14), (44, 160, 44), (214, 39, 40), (148, 103, 189),
           (140, 86, 75), (227, 119, 194), (127, 127, 127), (188, 189, 34), (23, 190, 207)]
# Errors (RMSE, grey levels of the 8-bit image) the verdict asks about.
VERDICT_ERRORS = [4.0, 2.0, 1.0, 0.5, 0.25]
PLOT_SIZE = (1000, 700)


def column(values):
    array = vtkFloatArray()
    for v in values:
        array.InsertNextValue(v)
    return array


AXIS_MARGIN = 1.15  # the axes' room beyond the values drawn (a factor on log axes)


def draw(series, out, title, xlabel, ylabel, log_x=False, log_y=False, legend_left=False):
    """series: list of (name, xs, ys, colour, dashed), each drawn in its order. Writes a PNG
    plot to out, the legend at the top right (or left, where the lines rise to the right)."""
    view = vtkContextView()
    window = view.GetRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*PLOT_SIZE)
    view.GetRenderer().SetBackground(1.0, 1.0, 1.0)
    chart = vtkChartXY()
    view.GetScene().AddItem(chart)
    chart.SetTitle(title)
    chart.SetShowLegend(True)
    chart.GetLegend().SetVerticalAlignment(vtkChartLegend.TOP)
    chart.GetLegend().SetHorizontalAlignment(vtkChartLegend.LEFT if legend_left else vtkChartLegend.RIGHT)
    tables = []  # the plots keep references, the tables must live until the render
    shown = ([], [])  # every value drawn along x and y: the axes hold them all
    for name, xs, ys, colour, dashed in series:
        pairs = [(x, y) for x, y in zip(xs, ys) if (x > 0 or not log_x) and (y > 0 or not log_y)]
        if not pairs:
            continue
        for p in pairs:
            shown[0].append(p[0])
            shown[1].append(p[1])
        table = vtkTable()
        xa, ya = column(p[0] for p in pairs), column(p[1] for p in pairs)
        xa.SetName(xlabel)
        ya.SetName(name)
        table.AddColumn(xa)
        table.AddColumn(ya)
        tables.append(table)
        # A single point (VolPack's one setting) is a marker: a line needs two.
        plot = chart.AddPlot(vtkChart.LINE if len(pairs) > 1 else vtkChart.POINTS)
        plot.SetInputData(table, 0, 1)
        plot.SetColor(*colour, 255)
        plot.SetWidth(2.0)
        plot.SetMarkerStyle(vtkPlotPoints.CIRCLE)
        if len(pairs) == 1:
            plot.SetMarkerSize(14.0)
        if dashed:  # a variant of the series before it, which the legend names
            plot.GetPen().SetLineType(vtkPen.DASH_LINE)
            plot.SetLegendVisibility(False)
    for axis, label, log, values in ((vtkAxis.BOTTOM, xlabel, log_x, shown[0]),
                                     (vtkAxis.LEFT, ylabel, log_y, shown[1])):
        chart.GetAxis(axis).SetTitle(label)
        chart.GetAxis(axis).SetLogScale(log)
        if values:  # VTK's automatic range can leave the largest points out
            lo, hi = min(values), max(values)
            lo, hi = (lo / AXIS_MARGIN, hi * AXIS_MARGIN) if log else (
                lo - (AXIS_MARGIN - 1) * (hi - lo), hi + (AXIS_MARGIN - 1) * (hi - lo))
            chart.GetAxis(axis).SetBehavior(vtkAxis.FIXED)
            chart.GetAxis(axis).SetUnscaledRange(lo, hi)  # data values, also on log axes
    view.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(out)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def read_accuracy(path):
    scenes = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            scenes.setdefault(row["scene"], []).append(row)
    return scenes


def slug(text):
    return "".join(c if c.isalnum() else "-" for c in text).strip("-")


def contender(mapper):
    """Who competes in the verdict: this mapper's modes and shading models are one."""
    return "this mapper" if mapper.startswith("PARC") else mapper


def verdict(rows):
    """Markdown: a one-line verdict, then for each error which mapper reaches it fastest
    (this mapper: its fastest acceleration mode and shading model) and how much slower the
    others are."""
    lines, winners = [], OrderedDict()
    for error in VERDICT_ERRORS:
        best = OrderedDict()  # contender -> its fastest row at or below the error
        for r in rows:
            key = contender(r["mapper"])
            if float(r["rmse"]) <= error and (
                    key not in best or float(r["median_s"]) < float(best[key]["median_s"])):
                best[key] = r
        missing = sorted({contender(r["mapper"]) for r in rows} - set(best))
        if not best:
            lines.append(f"- RMSE {error:g}: no mapper reaches it here.")
            continue
        ranked = sorted(best.values(), key=lambda r: float(r["median_s"]))
        winners.setdefault(ranked[0]["mapper"], []).append(f"{error:g}")
        fastest = float(ranked[0]["median_s"])
        parts = [f"{r['mapper']} {float(r['median_s']):.3f} s "
                 f"({float(r['median_s']) / fastest:.1f}x; sample distance "
                 f"{r['sample_distance']}, image sample distance {r['image_sample_distance']})"
                 for r in ranked]
        parts[0] = "**" + parts[0].replace(" (1.0x; ", " (") + "**"
        text = f"- RMSE {error:g}: " + ", ".join(parts)
        if missing:
            text += f"; never reached by {', '.join(missing)}"
        lines.append(text + ".")
    summary = "; ".join(f"{m} to RMSE {', '.join(e)}" for m, e in winners.items())
    return [f"**Verdict: fastest {summary}.**", ""] + lines


def accuracy(path, outdir):
    for scene, rows in read_accuracy(path).items():
        mappers = list(OrderedDict.fromkeys(r["mapper"] for r in rows))
        series = []
        for i, mapper in enumerate(mappers):
            for isd in sorted({r["image_sample_distance"] for r in rows}, key=float):
                chosen = [r for r in rows
                          if r["mapper"] == mapper and r["image_sample_distance"] == isd]
                if not chosen:
                    continue
                series.append((mapper,
                               [float(r["median_s"]) for r in chosen],
                               [float(r["rmse"]) for r in chosen],
                               PALETTE[i % len(PALETTE)], isd != "1"))
        name = f"accuracy-{slug(scene)}.png"
        draw(series, f"{outdir}/{name}",
             f"{scene}: error against frame time (dashed: image sample distance 2)",
             "median warm frame time (s)", "RMSE against the reference (grey levels)",
             log_x=True, log_y=True)
        print(f"### {scene}\n\n![{scene}]({name})\n")
        print("\n".join(verdict(rows)))
        print()


def lines(path, out, title, xlabel, ylabel, options):
    data = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            xs, ys = data.setdefault(row["series"], ([], []))
            xs.append(float(row["x"]))
            ys.append(float(row["y"]))
    series = []
    for i, (name, (xs, ys)) in enumerate(data.items()):
        series.append((name, xs, ys, PALETTE[i % len(PALETTE)], False))
        if "--mark-minimum" in options:
            best = min(range(len(ys)), key=ys.__getitem__)
            series.append((f"{name}: optimum", [xs[best]], [ys[best]], PALETTE[i % len(PALETTE)],
                           False))
    draw(series, out, title, xlabel, ylabel, "--log-x" in options, "--log-y" in options)


def main(argv):
    if len(argv) >= 3 and argv[0] == "accuracy":
        accuracy(argv[1], argv[2])
    elif len(argv) >= 6 and argv[0] == "lines":
        lines(*argv[1:6], argv[6:])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
