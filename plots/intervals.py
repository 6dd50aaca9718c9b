#!/usr/bin/python3
"""Collision sequences of free-space collapses, from the JSON that `granchain reproduce --figure
intervals` writes.

Usage: /usr/bin/python3 plots/intervals.py intervals.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) hard spheres: remaining time tau_n = t* - t_n to the collapse against the collision number n
    for a few launches (log tau against n: a geometric sequence is a straight line);
(b) the same against log n (a power of n is a straight line);
(c) collisions n(tau) before the hard sequence comes within tau of the collapse, against the k
    whose tau_c is tau, beside the soft spheres' n_tot(k);
(d) gaps between successive collisions in units of tau_c, soft spheres, one curve per k (a scaling
    plot: curves that coincide mean the sequences end at the cut-off the same way at every k), and
    the gaps between successive collisions of one pair at the largest k (dashed); overlapping
    contacts (negative gaps) are counted in the total but not drawn;
(e) collapse events per launch and collisions per event against k; cascades (events less than
    1000 tau_c apart) per launch and events per cascade (marker and line: the quantity; colour: e, as in
    every panel: blue 0.3, orange 0.5);
(f) particles per collapse event (soft, largest k) and in the final hard-sphere collapse.
"""
import sys

import numpy as np
from matplotlib.ticker import LogLocator

from plot_common import PAGE, SEQUENTIAL, colours, figure, load, plt, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig, axes = figure(PAGE, 4.8, nrows=2, ncols=3)
    ax = axes.ravel()
    styles = ["-", "--"]
    for j, h in enumerate(data["hard"]):
        for i, s in enumerate(h["samples"][:3]):
            n = np.array(s["n"], dtype=float)
            tau = np.array(s["tau"], dtype=float)
            label = r"$e = %g$" % h["e"] if i == 0 else None
            ax[0].semilogy(n, tau, styles[j % 2], lw=0.8, color="C%d" % j, label=label)
            ax[1].loglog(n, tau, styles[j % 2], lw=0.8, color="C%d" % j, label=label)
        k = np.array(h["k_equiv"], dtype=float)
        nn = np.array(h["n"], dtype=float)
        ne = np.array(h["n_error"], dtype=float)
        ax[2].errorbar(k, nn, yerr=ne, fmt="s--", ms=2.5, lw=0.8, color="C%d" % j,
                       label=r"hard, $e = %g$" % h["e"])
        if h["particles"]:
            p = np.array(h["particles"], dtype=float)
            ax[5].hist(p, bins=np.arange(0.5, data["N"] + 1.5), histtype="step", density=True, color="C%d" % j, lw=1.2,
                       label=r"hard, last, $e = %g$" % h["e"])
    for j, s in enumerate(data["soft"]):
        per_k = s["per_k"]
        k = np.array([p["k"] for p in per_k])
        n = np.array([p["n_tot"] for p in per_k])
        ne = np.array([p["n_tot_error"] for p in per_k])
        ax[2].errorbar(k, n, yerr=ne, fmt="o-", ms=2.5, lw=0.9, color="C%d" % j, label=r"soft $n_{\rm tot}$, $e = %g$" % s["e"])
        ev = np.array([p["events"] for p in per_k])
        eve = np.array([p["events_error"] for p in per_k])
        per = np.array([p["per_event"] for p in per_k])
        pere = np.array([p["per_event_error"] for p in per_k])
        ax[4].errorbar(k, ev, yerr=eve, fmt="o-", ms=2.5, color="C%d" % j)
        ax[4].errorbar(k, per, yerr=pere, fmt="s--", ms=2.5, color="C%d" % j)
        if "cascades" in per_k[0]:
            ca = np.array([p["cascades"] for p in per_k])
            cae = np.array([p["cascades_error"] for p in per_k])
            epc = np.array([p["events_per_cascade"] for p in per_k])
            ax[4].errorbar(k, ca, yerr=cae, fmt="^:", ms=2.5, color="C%d" % j)
            ax[4].plot(k, epc, "v-.", ms=2.5, lw=0.8, color="C%d" % j)
        edges = np.array(s["edges"], dtype=float)
        centres = np.sqrt(edges[1:] * edges[:-1])
        if j == 0:
            gap_colours = colours(len(per_k), SEQUENTIAL)
            for i, p in enumerate(per_k):
                h = np.array(p["gap_hist"], dtype=float)[1:-1]
                ax[3].loglog(centres, h / np.log10(edges[1:] / edges[:-1]), "o-", ms=2, lw=0.7, color=gap_colours[i])
            # The colour bar of k beside (d), a strip that covers no data.
            logk = [np.log10(p["k"]) for p in per_k]
            bar = fig.colorbar(plt.cm.ScalarMappable(norm=plt.Normalize(min(logk), max(logk)), cmap=SEQUENTIAL),
                               cax=ax[3].inset_axes([1.03, 0.0, 0.04, 1.0]))
            bar.set_label(r"$\log_{10} k$", labelpad=1)
            bar.ax.tick_params(labelsize=6)
            pair = np.array(per_k[-1]["pair_gap_hist"], dtype=float)
            if pair.sum() > 0:
                ax[3].loglog(centres, pair[1:-1] / pair.sum() / np.log10(edges[1:] / edges[:-1]), "k--", lw=0.8,
                             label=r"same pair, $k = 10^{%d}$" % round(np.log10(per_k[-1]["k"])))
            ax[3].set_title(r"(d) soft, $e = %g$: gaps" % s["e"], loc="left")
        last = per_k[-1]
        ph = np.array(last["particles_hist"], dtype=float)
        if ph.sum() > 0:
            ax[5].step(np.arange(len(ph)), ph / ph.sum(), where="mid", color="C%d" % j, lw=0.8, ls=":",
                       label=r"soft, $k = 10^{%d}$, $e = %g$" % (round(np.log10(last["k"])), s["e"]))
    ax[0].set_xlabel(r"collision number $n$")
    ax[0].set_ylabel(r"$\tau_n = t^* - t_n$")
    ax[0].set_title("(a) hard: geometric is straight", loc="left")
    ax[1].set_xlabel(r"collision number $n$")
    ax[1].set_ylabel(r"$\tau_n$")
    ax[1].set_title(r"(b) a power of $n$ is straight", loc="left")
    ax[2].set_xscale("log")
    ax[2].set_yscale("log")
    ax[2].set_xlabel(r"$k$ (hard: $\tau_c(k) = \tau$)")
    ax[2].set_ylabel("collisions")
    ax[2].set_title("(c) hard and soft counts", loc="left")
    ax[3].set_xlabel(r"gap $/\,\tau_c$")
    ax[3].set_ylabel("fraction per decade")
    ax[3].axvline(data["event_gap"], color="k", lw=0.5, ls="--")
    ax[4].set_xscale("log")
    ax[4].set_yscale("log")
    ax[4].set_xlabel(r"$k$")
    ax[4].set_ylabel("count per launch, event or cascade")
    ax[4].set_title("(e) soft: collapse events, cascades", loc="left")
    ax[5].set_xlabel("particles")
    ax[5].set_ylabel("fraction")
    ax[5].set_title("(f) particles in a collapse", loc="left")
    for a in ax:
        for axis in (a.xaxis, a.yaxis):
            if axis.get_scale() == "log":  # a tick label at every decade that fits, not one
                axis.set_major_locator(LogLocator(base=10, numticks=6))
    # Legends where the axes have been given room for them, off the data: (c) and (f) above their
    # curves, (e) below them.
    bottom, top = ax[2].get_ylim()
    ax[2].set_ylim(bottom, top * 30)
    ax[5].set_ylim(0, 1.75)
    for i, place in ((0, "best"), (1, "best"), (2, "upper left"), (3, "best"), (5, "upper right")):
        ax[i].legend(handlelength=1.5, loc=place)
    # (e): the marker and line say which quantity, the colour which e.
    key = [plt.Line2D([], [], color="0.2", ls=ls, marker=m, ms=2.5) for ls, m in (("-", "o"), ("--", "s"), (":", "^"), ("-.", "v"))]
    bottom, top = ax[4].get_ylim()
    ax[4].set_ylim(bottom / 30, top)  # room below the curves for the legend
    ax[4].legend(key, ["events per launch", "collisions per event", "cascades per launch", "events per cascade"],
                 loc="lower right", handlelength=2.2, ncol=1)
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
