#!/usr/bin/python3
"""Contact durations of the driven column against height, per N, from
`granchain reproduce --figure contacts` (contacts.json).

Usage: /usr/bin/python3 plots/contacts.py contacts.json PREFIX   -> PREFIX.png and PREFIX.pdf
One column per choice of e (N(1 - e) = 2, N(1 - e) = 5, e = 0.3), one colour per N: (top) the
fraction of the window each pair (i, i+1) spends in contact and (middle) its mean contact duration
in units of tau_c, against the pair's height i/N, at the smallest k (where contacts last longest);
(third row) the share of the
bottom tenth's contact time spent in contacts longer than 2 tau_c (held by three or more
particles) against k, with the replicas' error; (last row) the distribution of the bottom tenth's
contact durations at the smallest k: the fraction of its contacts per octave of duration / tau_c.
"""
import sys

import numpy as np
from matplotlib.ticker import FormatStrFormatter, NullFormatter

from plot_common import PAGE, colours, figure, legend_axes, load, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    choices = data["choices"]
    Ns = sorted({col["N"] for ch in choices for col in ch["columns"]})
    palette = dict(zip(Ns, colours(max(len(Ns), 2))))
    fig, axes = figure(PAGE, 8.0, nrows=4, ncols=len(choices) + 1,
                       gridspec_kw={"width_ratios": [1] * len(choices) + [0.32]}, squeeze=False)
    handles = {}
    for c, ch in enumerate(choices):
        a_f, a_m, a_s, a_h = axes[0][c], axes[1][c], axes[2][c], axes[3][c]
        for col in ch["columns"]:
            ks = col["k"]
            if not ks:
                continue
            top = min(ks, key=lambda x: x["k"])
            colour = palette[col["N"]]
            line, = a_f.plot(top["height"], top["fraction"], color=colour)
            mean = np.array(top["mean"], dtype=float)
            a_m.plot(top["height"], np.where(mean > 0, mean, np.nan), color=colour)  # (a pair without contacts: none)
            handles[col["N"]] = line
            k = np.array([x["k"] for x in ks])
            order = np.argsort(k)
            s = np.array([np.nan if x["bottom_long_share"] is None else x["bottom_long_share"] for x in ks], dtype=float)[order]
            s_err = np.array([np.nan if x["bottom_long_share_err"] is None else x["bottom_long_share_err"] for x in ks],
                             dtype=float)[order]
            a_s.errorbar(k[order], s, yerr=s_err, color=colour, fmt="o-", ms=2.5, capsize=1.5)
            hist = top["bottom_histogram"]
            counts = np.array(hist["counts"], dtype=float)
            if counts.sum() > 0:
                bins = hist["first_bin"] + np.arange(len(counts))
                centre = np.exp2(data["log2_min"] + (bins + 0.5) / data["bins_per_octave"])
                density = counts / counts.sum() * data["bins_per_octave"]  # per octave
                a_h.plot(centre, np.where(density > 0, density, np.nan), color=colour, marker=".", ms=2)
        ks_all = sorted({x["k"] for col in ch["columns"] for x in col["k"]})
        letters = "abc"[c]
        a_f.set_title("(%s1) %s" % (letters, ch["label"]), loc="left")
        if ks_all:
            a_f.text(0.97, 0.95, "k = %.0e" % ks_all[0], transform=a_f.transAxes, ha="right", va="top", fontsize=7)
        a_m.set_title("(%s2) mean contact duration" % letters, loc="left")
        a_s.set_title("(%s3) bottom tenth, > %g $\\tau_c$" % (letters, data["long_contact"]), loc="left")
        a_h.set_title("(%s4) bottom tenth's durations" % letters, loc="left")
        a_h.set_xscale("log", base=2)
        a_h.set_yscale("log")
        a_h.axvline(data["long_contact"], color="0.6", lw=0.6, ls=":")
        a_h.set_xlabel(r"duration [$\tau_c$]")
        a_f.set_ylim(0, 1.02)
        a_m.set_yscale("log")
        a_m.yaxis.set_major_formatter(FormatStrFormatter("%g"))
        lo, hi = a_m.get_ylim()
        # Under a decade the major ticks may show a single label: the minor ones are labelled then.
        a_m.yaxis.set_minor_formatter(FormatStrFormatter("%g") if hi / lo < 10 else NullFormatter())
        a_m.axhline(1.0, color="0.6", lw=0.6, ls=":")
        a_s.set_xscale("log")
        a_s.set_ylim(-0.02, 1.02)
        for ax in (a_f, a_m):
            ax.set_xlim(0, 1)
            ax.set_xlabel(r"pair height $i/N$")
        a_s.set_xlabel(r"$k$")
        if c == 0:
            a_f.set_ylabel("fraction of the window")
            a_m.set_ylabel(r"duration [$\tau_c$]")
            a_s.set_ylabel("share of contact time")
            a_h.set_ylabel("contacts per octave")
    for row in range(4):
        axes[row][-1].set_axis_off()
    names = sorted(handles)
    legend_axes(axes[0][-1], [handles[n] for n in names], ["N = %d" % n for n in names], loc="center left")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
