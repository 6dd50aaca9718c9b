"""Shared by the plot scripts: matplotlib without a display, reading the JSON granchain writes,
saving a figure as PREFIX.png and PREFIX.pdf (each written whole or not at all), and the one style
of every figure: sizes for a journal's column (3.4 in) or page (7.0 in), fonts of 7-8 pt at that
size, colour maps without white or yellow ends, and brackets (intervals) drawn unlike error bars."""
import json
import os
import signal
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (re-exported)
import numpy as np  # noqa: E402
from matplotlib.colors import LinearSegmentedColormap  # noqa: E402
from matplotlib.path import Path  # noqa: E402

# Figure widths in inches: one journal column, or the whole page.
COLUMN = 3.4
PAGE = 7.0

# Text is drawn at these sizes at print size (the figure is never scaled down): labels 8 pt,
# tick labels, legends and annotations 7 pt.
plt.rcParams.update({
    "font.size": 8,
    "axes.titlesize": 8,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 7,
    "figure.titlesize": 8,
    "legend.handlelength": 1.8,
    "legend.borderaxespad": 0.3,
    "legend.labelspacing": 0.3,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    "lines.linewidth": 0.9,
    "lines.markersize": 3,
    "errorbar.capsize": 1.5,
    "pdf.fonttype": 42,  # TrueType in the PDF: text a journal's tools can edit
    "savefig.dpi": 300,
})

# Sequential maps cut before their light end: viridis without its yellow, plasma without its
# yellow; every colour reads on white.
SEQUENTIAL = LinearSegmentedColormap.from_list("viridis_dark", plt.get_cmap("viridis")(np.linspace(0.0, 0.82, 256)))
SEQUENTIAL_2 = LinearSegmentedColormap.from_list("plasma_dark", plt.get_cmap("plasma")(np.linspace(0.0, 0.78, 256)))

# A bracket "[" as a marker: the legend's symbol for an interval drawn by bracket().
BRACKET_MARKER = Path([(0.4, -1.0), (0.0, -1.0), (0.0, 1.0), (0.4, 1.0)],
                      [Path.MOVETO, Path.LINETO, Path.LINETO, Path.LINETO])


def _end_on_sigterm(signum, frame):
    # SIGTERM (also sent when granchain, which started this script, ends) ends the script through
    # SystemExit, so that save_file removes its unfinished temporary file.
    raise SystemExit(128 + signum)


signal.signal(signal.SIGTERM, _end_on_sigterm)


def load(path):
    with open(path) as f:
        return json.load(f)


def usage(doc, argv, count):
    """True (after printing the usage) when argv does not hold `count` arguments."""
    if len(argv) != count + 1:
        sys.stderr.write(doc)
        return True
    return False


def figure(width, height, **kwargs):
    """A figure of width x height inches (width COLUMN or PAGE) laid out by matplotlib's constrained
    layout, so that the saved file has exactly that size; kwargs go to plt.subplots (nrows, ncols,
    gridspec_kw, ...); with nrows = 0 only the figure is returned."""
    if kwargs.get("nrows") == 0:
        return plt.figure(figsize=(width, height), layout="constrained")
    return plt.subplots(figsize=(width, height), layout="constrained", **kwargs)


def colours(n, cmap=SEQUENTIAL):
    """n colours spread over cmap (a single one: its dark end)."""
    return [cmap(i / max(1, n - 1)) for i in range(n)]


def legend_axes(ax, handles, labels, **kwargs):
    """Uses ax (an axes of its own in the layout, frame off) for a legend of handles and labels, so
    that the legend covers no data and the layout keeps room for it."""
    ax.set_axis_off()
    kwargs.setdefault("loc", "center")
    return ax.legend(handles, labels, frameon=False, **kwargs)


def bracket(ax, x, lo, hi, color, offset_pt=0.0, lw=1.2, **kwargs):
    """The interval lo <= y <= hi at x drawn as a bracket "[": a vertical line with end ticks that
    point right. It is clipped to the y range the axes have now (set it first): an end beyond it
    is an arrow head at the axes' edge instead of a tick. offset_pt moves it sideways by that many
    points, to keep it apart from a point at the same x. No marker at its middle: unlike an error
    bar it does not stand for a value with its error."""
    from matplotlib.transforms import ScaledTranslation
    y0, y1 = ax.get_ylim()
    bottom, top = max(min(lo, hi), y0), min(max(lo, hi), y1)
    if bottom > y1 or top < y0:
        return
    shift = ax.transData + ScaledTranslation(offset_pt / 72.0, 0, ax.figure.dpi_scale_trans)
    ax.plot([x, x], [bottom, top], "-", color=color, lw=lw, transform=shift, solid_capstyle="butt", **kwargs)
    for end, beyond, head in ((bottom, min(lo, hi) < y0, "v"), (top, max(lo, hi) > y1, "^")):
        if beyond:
            ax.plot([x], [end], head, color=color, ms=4, transform=shift, clip_on=False, **kwargs)
        else:
            ax.plot([x], [end], marker=1, color=color, ms=4, mew=lw, transform=shift, **kwargs)  # tick to the right


def bracket_handle(color, lw=1.2):
    """The legend's symbol for bracket()."""
    return plt.Line2D([], [], ls="none", marker=BRACKET_MARKER, ms=7, mew=lw, mfc="none", color=color)


def save_file(fig, path, **kwargs):
    """Writes the figure to path whole or not at all: a temporary file beside it, then a rename."""
    fmt = path.rsplit(".", 1)[-1]
    tmp = "%s.tmp%d.%s" % (path, os.getpid(), fmt)
    try:
        fig.savefig(tmp, format=fmt, **kwargs)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def save(fig, prefix):
    """PREFIX.png (300 dpi) and PREFIX.pdf at the figure's own size (no tight box: the width stays
    a column's or a page's)."""
    save_file(fig, prefix + ".png")
    save_file(fig, prefix + ".pdf")
