#!/usr/bin/python3
"""The onset of collapse per drive from `granchain reproduce --figure drives-onset` (drives-onset.json).

Usage: /usr/bin/python3 plots/drive_onset.py drives-onset.json PREFIX   -> PREFIX.png and PREFIX.pdf
If 1 - e_c = A/N, then N(1 - e_c) = A at every N: each panel draws N(1 - e_c) against N (log axis)
for every drive (one colour each, points a little apart sideways), with one standard error, and
the drive's fitted A as a horizontal line. (a) e_c1 from b -> 0; (b) the classification boundary
(a bracket: between the last collapsing and the first uncollapsing e); (c) e_c2 where the curvature
of n_coll(log k) changes sign. Grey lines: the published onsets 2.5 (Luding et al., sine) and 2.6
(the paper's e_c1 and Bernu et al.'s drives), and the paper's 3.0 for e_c2.
"""
import sys

import numpy as np

from plot_common import PAGE, bracket, bracket_handle, figure, legend_axes, load, plt, save, usage

COLOURS = {"thermal": "#222222", "sine": "#1f4e9c", "sawtooth": "#c0392b", "quadratic": "#2a9d8f"}
MARKERS = {"thermal": "o", "sine": "s", "sawtooth": "^", "quadratic": "D"}


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, axes = figure(PAGE, 2.6, ncols=4, gridspec_kw={"width_ratios": [1, 1, 1, 0.62]})
    panels = (("e_c1", "A1", r"(a) $N(1-e_{c1})$, $b \to 0$", (2.6, 2.5)),
              ("boundary", "A1_boundary", "(b) classification boundary", (2.6, 2.5)),
              ("e_c2_sign", "A2_sign", r"(c) $N(1-e_{c2})$, curvature sign", (3.0,)))
    drives = data["drives"]
    Ns = sorted({f["N"] for d in drives for f in d["families"]})
    handles, labels = [], []
    for col, (key, fit_key, title, refs) in enumerate(panels):
        ax = axes[col]
        ax.set_xscale("log")
        values = []
        for d in drives:
            for f in d["families"]:
                c = f.get(key)
                if c:
                    values += [f["N"] * (1 - c["high"]), f["N"] * (1 - c["low"]), f["N"] * (1 - c["value"])]
        lo, hi = (min(values + list(refs)), max(values + list(refs))) if values else (0, 5)
        pad = 0.08 * (hi - lo + 0.5)
        ax.set_ylim(max(0, lo - pad), hi + pad)
        if Ns:
            ax.set_xlim(Ns[0] / 1.25, Ns[-1] * 1.25)
        for r, ls in zip(refs, ("--", ":")):
            ax.axhline(r, color="0.55", ls=ls, lw=0.7)
        for i, d in enumerate(drives):
            name = d["drive"]
            colour = COLOURS.get(name, "0.3")
            factor = 1.04 ** (i - 1.5)  # sideways, on the log axis
            for f in d["families"]:
                c = f.get(key)
                if not c:
                    continue
                x = f["N"] * factor
                if key == "boundary":
                    bracket(ax, x, f["N"] * (1 - c["high"]), f["N"] * (1 - c["low"]), colour)
                else:
                    ax.errorbar(x, f["N"] * (1 - c["value"]), yerr=f["N"] * c["error"], fmt=MARKERS.get(name, "o"),
                                color=colour, ms=3, capsize=1.5)
            if d.get(fit_key):
                A = d[fit_key]["A"]
                err = d[fit_key]["error"]
                ax.axhspan(A - err, A + err, color=colour, alpha=0.12, lw=0)
                ax.axhline(A, color=colour, lw=0.8)
        ax.set_title(title, loc="left")
        ax.set_xlabel(r"$N$")
        ax.set_xticks(Ns)
        ax.set_xticklabels([str(n) if n in (10, 20, 50, 100) or len(Ns) < 5 else "" for n in Ns], fontsize=6)
        ax.minorticks_off()
        if col == 0:
            ax.set_ylabel(r"$N(1-e_c)$")
    for d in drives:
        name = d["drive"]
        colour = COLOURS.get(name, "0.3")
        handles.append((plt.Line2D([], [], ls="none", marker=MARKERS.get(name, "o"), color=colour, ms=3.5),
                        plt.Line2D([], [], color=colour, lw=0.8)))
        fit = d.get("A1")
        labels.append(name + ("" if not fit else "\n$A_1$ = %.2f $\\pm$ %.2f" % (fit["A"], fit["error"])))
    handles.append(bracket_handle("0.3"))
    labels.append("bracket: an interval,\nnot an error bar")
    handles.append(plt.Line2D([], [], color="0.55", ls="--", lw=0.7))
    labels.append("2.6 (paper, Bernu et al.);\n3.0 (paper, $e_{c2}$)")
    handles.append(plt.Line2D([], [], color="0.55", ls=":", lw=0.7))
    labels.append("2.5 (Luding et al.)")
    legend_axes(axes[3], handles, labels, loc="center left")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
