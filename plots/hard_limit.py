#!/usr/bin/python3
"""The driven column's hard-sphere limit, from the JSON that `granchain reproduce --figure limit-hard`
writes.

Usage: /usr/bin/python3 plots/hard_limit.py DATA.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a)-(d) one panel per N: the exact engine's n_coll against k (one curve per e, error bars one
    standard error), and the hard-sphere engine's n_coll at the same e as a horizontal line with its
    band (the replicas' standard error); a series whose hard spheres collapse ends in an open marker;
(e) the fraction of hard replicas that collapse against N(1 - e), one colour per N, from the
    initial state (filled) and from the soft column's state (open);
(f) when they collapse: the time from the start (initial state) or from the hand-over at the end of
    the transient (soft start) of each collapse against N(1 - e), same markers.
"""
import sys

import numpy as np

from plot_common import PAGE, SEQUENTIAL, colours, figure, load, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    series, thresholds = data["series"], data["thresholds"]
    ns = sorted({s["N"] for s in series} | {t["N"] for t in thresholds})
    fig = figure(PAGE, 4.6, nrows=0)
    grid = fig.add_gridspec(2, 3)
    panels = [fig.add_subplot(grid[i // 3, i % 3]) for i in range(6)]
    soft_axes = panels[:4]
    letters = "abcd"
    for j, N in enumerate(ns[:4]):
        ax = soft_axes[j]
        mine = [s for s in series if s["N"] == N]
        palette = colours(max(len(mine), 2), SEQUENTIAL)
        for i, s in enumerate(mine):
            k = np.log10(np.array(s["k"], dtype=float))
            y = np.array(s["y"], dtype=float)
            err = np.array([np.nan if v is None else v for v in s["error"]], dtype=float)
            color = palette[i]
            ax.errorbar(k, y, yerr=err, fmt="o-", ms=2.5, lw=0.8, color=color, label=r"$e = %g$" % s["e"])
            hard = s.get("hard")
            if hard:
                ax.axhline(hard["value"], color=color, lw=0.6, ls="--")
                if hard.get("error") is not None:
                    ax.axhspan(hard["value"] - hard["error"], hard["value"] + hard["error"], color=color, alpha=0.2, lw=0)
            elif s.get("hard_collapses") and len(k):
                ax.plot(k[-1], y[-1], "o", ms=5, mfc="none", color=color)
        ax.set_yscale("log")
        ax.set_xlabel(r"$\log_{10} k$")
        ax.set_ylabel(r"$n_{\rm coll}$")
        ax.set_title("(%s) N = %d" % (letters[j], N), loc="left")
        ax.legend(loc="upper left", frameon=False, fontsize=6)
    for ax in soft_axes[len(ns):]:
        ax.set_visible(False)
    ax_e, ax_f = panels[4], panels[5]
    palette = colours(max(len(ns), 2), SEQUENTIAL)
    for j, N in enumerate(ns):
        for soft_start in (False, True):
            rows = sorted((t for t in thresholds if t["N"] == N and t["soft_start"] == soft_start), key=lambda t: t["c"])
            if not rows:
                continue
            c = np.array([t["c"] for t in rows])
            done = np.array([t["ran"] + t["collapsed"] for t in rows], dtype=float)
            frac = np.where(done > 0, np.array([t["collapsed"] for t in rows]) / np.maximum(done, 1), np.nan)
            style = dict(color=palette[j], ms=3.5, lw=0.8, mfc="none" if soft_start else palette[j])
            label = "N = %d, %s" % (N, "soft start" if soft_start else "initial state")
            ax_e.plot(c, frac, ("s--" if soft_start else "o-"), label=label, **style)
            for t in rows:
                if t["waits"]:
                    ax_f.plot([t["c"]] * len(t["waits"]), t["waits"], "s" if soft_start else "o", ms=3,
                              color=palette[j], mfc="none" if soft_start else palette[j])
    ax_e.set_xlabel(r"$N(1-e)$")
    ax_e.set_ylabel("fraction of replicas that collapse")
    ax_e.set_title("(e) collapsing replicas (of %d)" % data.get("replicas", 0), loc="left")
    ax_e.legend(loc="upper left", frameon=False, fontsize=6)
    ax_f.set_yscale("log")
    ax_f.set_xlabel(r"$N(1-e)$")
    ax_f.set_ylabel("time to the collapse")
    ax_f.set_title("(f) when they collapse", loc="left")
    fig.suptitle(data.get("title", "") + "\n(a)-(d) exact engine (points), hard spheres (dashed)\n"
                 "(e), (f) hard spheres from the initial state (filled), from the soft column (open)")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
