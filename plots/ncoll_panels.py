#!/usr/bin/python3
"""n_coll(k, e) panels in the manner of the paper's Fig. cfreqlogN25, from `granchain analyze --json`.

Usage: /usr/bin/python3 plots/ncoll_panels.py analysis.json PREFIX
For every (engine, N, T0) of the analysis writes PREFIX_N<N>_T0<T0>_<engine>.png and .pdf, a
page-wide figure with
(a) n_coll against log10 k for the critical region 1 - 5/N <= e <= 1 - 2.5/N (the paper's
    0.80 ... 0.90 at N = 25), with the fitted a + b log10 k where logarithmic; for N < 10 every e,
(b) the same for 1 - 3.25/N <= e <= 1 - 2.5/N (0.87 ... 0.90 at N = 25); for N < 10 the e around
    the free-space critical values e_c(3) ... e_c(N + 1) given as ec_lines,
(c) log10 n_coll against log10 k for e = 0.1, 0.2, ..., 1.0, with the fitted c k^alpha where
    power-law,
(d) n_coll against e for every k, with e_c1 (and its error), the classification boundary and the
    e_c2 bracket, and the paper's e_c1 and e_c2 where the analysis carries them ("paper"); for
    N >= 10 the critical region enlarged in a panel of its own beside it (d'),
(e) the local exponent per decade of k of the curves at e = 0.1 ... 0.4 (Table 1's), with their
    global alpha as dashed lines: the drift the global fit averages.
A panel whose e range holds no curve shows every curve instead. Colours encode e (colour bars) in
(a)-(c), (e) and k in (d) (legend below). Error bars are one standard error; crosses: a run whose
window was not stationary. Prints the files written. The functions against_log_k and against_e
also draw the paper's Figs. cflogk and cfe (small_n.py).
"""
import sys

import numpy as np

from plot_common import PAGE, SEQUENTIAL, SEQUENTIAL_2, colours, figure, legend_axes, load, plt, save, usage


def arrays(c):
    k = np.array([p["k"] for p in c["n_coll_of_k"]])
    n = np.array([p["n_coll"] for p in c["n_coll_of_k"]])
    s = np.array([p["error"] for p in c["n_coll_of_k"]])
    return k, n, s


def in_range(curves, lo, hi):
    chosen = [c for c in curves if lo - 1e-9 <= c["e"] <= hi + 1e-9]
    return chosen if chosen else curves


def e_norm(curves):
    es = [c["e"] for c in curves]
    lo, hi = min(es), max(es)
    return plt.Normalize(lo, hi) if hi > lo else plt.Normalize(lo - 0.05, hi + 0.05)  # one e: a bar around it


def e_colorbar(fig, ax, norm):
    """The colour bar of e in a narrow strip just right of ax (an inset, which the layout keeps room for)."""
    sm = plt.cm.ScalarMappable(norm=norm, cmap=SEQUENTIAL)
    bar = fig.colorbar(sm, cax=ax.inset_axes([1.03, 0.0, 0.04, 1.0]))
    bar.set_label("$e$", labelpad=1)
    bar.ax.tick_params(labelsize=6)
    return bar


def against_log_k(ax, curves, k_min, log_n, title, norm):
    """n_coll (or log10 n_coll) against log10 k, one colour per e (norm: e to the colour map), with
    the fitted a + b log10 k of logarithmic curves (or c k^alpha of power-law ones) over the fit's range."""
    for c in curves:
        colour = SEQUENTIAL(norm(c["e"]))
        k, n, s = arrays(c)
        x = np.log10(k)
        y, dy = (np.log10(n), s / (n * np.log(10))) if log_n else (n, s)
        marker = "o" if not c.get("non_stationary_k") else "x"
        ax.errorbar(x, y, yerr=dy, fmt=marker, ms=2, color=colour, capsize=1)
        if c.get("classified"):
            xa = x[k >= k_min] if np.any(k >= k_min) else x
            xx = np.linspace(xa.min(), xa.max(), 50)  # the fit's own range
            if not log_n and c["regime"] == "logarithmic":
                ax.plot(xx, c["log_fit"]["a"] + c["log_fit"]["b"] * xx, "-", color=colour, lw=0.6)
            if log_n and c["regime"] == "power-law":
                pf = c["power_fit"]
                ax.plot(xx, np.log10(pf["c"]) + pf["alpha"] * xx, "-", color=colour, lw=0.6)
    ax.set_xlabel(r"$\log_{10} k$")
    ax.set_ylabel(r"$\log_{10} n_{\rm coll}$" if log_n else r"$n_{\rm coll}$")
    ax.set_title(title, loc="left")


def k_styles(curves):
    """Each k of the curves with its colour (dark to light with k) and legend label."""
    ks = sorted({p["k"] for c in curves for p in c["n_coll_of_k"]})
    return [(k, colour, r"$k = 10^{%d}$" % round(np.log10(k))) for k, colour in zip(ks, colours(len(ks), SEQUENTIAL_2))]


def against_e(ax, family, curves, xlim=None):
    """n_coll against e, one curve per k, with the critical values of the family (vertical lines and
    bands) over e in xlim (all e without). Returns the legend's handles and labels."""
    handles, labels = [], []
    for k, colour, label in k_styles(curves):
        pts = sorted((c["e"], p["n_coll"], p["error"]) for c in curves for p in c["n_coll_of_k"] if p["k"] == k)
        e, n, s = (np.array(v) for v in zip(*pts))
        if xlim:
            sel = (e >= xlim[0] - 1e-9) & (e <= xlim[1] + 1e-9)
            e, n, s = e[sel], n[sel], s[sel]
        h = ax.errorbar(e, n, yerr=s, fmt="o-", ms=1.8, lw=0.7, color=colour, capsize=1)
        handles.append(h)
        labels.append(label)

    def mark(artist, label):
        handles.append(artist)
        labels.append(label)

    for i, ec in enumerate(family.get("ec_lines", [])):  # Fig. cfe: e_c(3) ... e_c(N+1)
        line = ax.axvline(ec, ls=":", color="0.35", lw=0.8)
        if i == 0:
            mark(line, r"free space: $e_c(3), \ldots, e_c(N+1)$")
    est = family.get("e_c1_estimate") or {}
    if family.get("e_c2"):
        mark(ax.axvspan(family["e_c2"]["low"], family["e_c2"]["high"], color="0.85", lw=0), r"$e_{c2}$ bracket")
    if est.get("boundary"):
        b = est["boundary"]
        mark(ax.axvspan(b["last_collapsing_e"], b["first_uncollapsing_e"], color="#2a9d8f", alpha=0.35, lw=0),
             "classification boundary")
    if family.get("e_c1"):
        v, err = family["e_c1"]["value"], family["e_c1"]["error"]
        ax.axvspan(v - err, v + err, color="0.6", alpha=0.3, lw=0)
        mark(ax.axvline(v, ls="--", color="k", lw=0.8), r"$e_{c1}$ ($b \to 0$) and its error")
    paper = family.get("paper") or {}
    if "e_c1" in paper:
        mark(ax.axvline(paper["e_c1"], ls="-.", color="#c0392b", lw=0.9), r"paper: $e_{c1}$")
    if "e_c2_low" in paper:
        mark(ax.axvspan(paper["e_c2_low"], paper["e_c2_high"], fill=False, hatch="////", edgecolor="#c0392b", lw=0),
             r"paper: $e_{c2}$")
    if xlim:
        ax.set_xlim(*xlim)
    ax.set_xlabel("$e$")
    ax.set_ylabel(r"$n_{\rm coll}$")
    return handles, labels


def local_exponents(ax, curves, fig):
    """(e): local exponent per decade of k against the decade's middle, for e = 0.1 ... 0.4."""
    chosen = [c for c in curves if c.get("local_exponents") and any(abs(c["e"] - x) < 1e-9 for x in (0.1, 0.2, 0.3, 0.4))]
    if not chosen:
        ax.set_axis_off()
        return
    norm = plt.Normalize(0.1, 0.4)
    for c in chosen:
        colour = SEQUENTIAL(norm(c["e"]))
        le = c["local_exponents"]
        x = np.array([0.5 * (np.log10(p["k1"]) + np.log10(p["k2"])) for p in le])
        y = np.array([p["alpha"] for p in le])
        dy = np.array([p["error"] for p in le])
        ax.errorbar(x, y, yerr=dy, fmt="o-", ms=2, lw=0.7, color=colour, capsize=1)
        if c.get("regime") == "power-law":
            ax.axhline(c["power_fit"]["alpha"], ls="--", lw=0.6, color=colour)
    e_colorbar(fig, ax, norm)
    ax.set_xlabel(r"$\log_{10} k$ (middle of each decade)")
    ax.set_ylabel(r"local exponent $\Delta \ln n_{\rm coll} / \Delta \ln k$")
    ax.set_title(r"(e) local $\alpha$; dashed: global", loc="left")


def draw(family, prefix, k_min):
    curves = [c for c in family["curves"] if c["n_coll_of_k"]]
    if not curves:
        return None
    N = family["N"]
    if N >= 10:
        wide = in_range(curves, 1 - 5.0 / N, 1 - 2.5 / N)
        narrow = in_range(curves, 1 - 3.25 / N, 1 - 2.5 / N)
    else:  # small N: every e, then the region of the free-space e_c(n)
        wide = curves
        lines = family.get("ec_lines") or []
        narrow = in_range(curves, min(lines) - 0.02, max(lines) + 0.02) if lines else curves
    tenths = [c for c in curves if abs(10 * c["e"] - round(10 * c["e"])) < 1e-9] or curves
    tenths_title = "(c) $e$ = " + (", ".join("%g" % c["e"] for c in tenths) if len(tenths) <= 4 else "%g, %g, …" % (tenths[0]["e"], tenths[1]["e"]))
    crit = [family["e_c1"]["value"]] if family.get("e_c1") else []
    es = sorted(c["e"] for c in curves)
    zoom = None
    if N >= 10 and (family.get("e_c2") or crit):  # the critical region, enlarged in (d')
        lo = min([family["e_c2"]["low"]] if family.get("e_c2") else crit) - 0.03
        hi = max(crit + ([family["e_c2"]["high"]] if family.get("e_c2") else [])) + 0.03
        if sum(1 for e in es if lo <= e <= hi) >= 3:
            zoom = (lo, hi)

    fig = figure(PAGE, 6.0, nrows=0)
    grid = fig.add_gridspec(3, 3, height_ratios=[1, 1, 0.2])
    top = [fig.add_subplot(grid[0, i]) for i in range(3)]
    for ax, chosen, log_n, title in ((top[0], wide, False, "(a) $e$ = %.3g … %.3g"), (top[1], narrow, False, "(b) $e$ = %.3g … %.3g"),
                                     (top[2], tenths, True, tenths_title)):
        norm = e_norm(chosen)
        label = title % (min(c["e"] for c in chosen), max(c["e"] for c in chosen)) if "%" in title else title
        against_log_k(ax, chosen, k_min, log_n, label, norm)
        e_colorbar(fig, ax, norm)
    if zoom:
        ax_d, ax_z = fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1])
    else:
        ax_d, ax_z = fig.add_subplot(grid[1, 0:2]), None
    handles, labels = against_e(ax_d, family, curves)
    ax_d.set_title(r"(d) $n_{\rm coll}$ against $e$", loc="left")
    if ax_z is not None:
        against_e(ax_z, family, curves, zoom)
        ax_d.axvspan(*zoom, fill=False, edgecolor="0.4", lw=0.6, ls="--")  # where (d') enlarges
        ax_z.set_title(r"(d$'$) the dashed box of (d)", loc="left")
    local_exponents(fig.add_subplot(grid[1, 2]), curves, fig)
    legend_axes(fig.add_subplot(grid[2, :]), handles, labels, ncol=6, columnspacing=1.2)
    drive = ""
    if isinstance(family.get("drive"), str):  # a vibrating plate (docs/drives.md)
        drive = r", %s plate $A = %.4g$, $\omega = %g$" % (family["drive"], family["plate_A"], family["plate_omega"])
    fig.suptitle(r"$N = %d$, $k_B T_0 = %g$, engine %s%s (crosses: window not stationary)" % (N, family["T0"], family["engine"], drive))
    stem = family.get("stem") or "%s_N%d_T0%g_%s" % (prefix, N, family["T0"], family["engine"])
    save(fig, stem)
    plt.close(fig)
    return stem + ".png"


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    analysis = load(argv[1])
    for family in analysis["families"]:
        out = draw(family, argv[2], analysis.get("k_min", 0.0))
        if out:
            print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
