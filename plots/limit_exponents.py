#!/usr/bin/python3
"""How a collision count grows as k -> infinity, from the JSON that `granchain reproduce --figure
limit-free` or `limit-driven` writes.

Usage: /usr/bin/python3 plots/limit_exponents.py DATA.json PREFIX   -> PREFIX.png and PREFIX.pdf
(a) the local exponent d ln n / d ln k per decade against k, one curve per series, with errors;
(b) the local exponent times ln k at the middle of its interval: the beta of (ln k)^beta, flat for
    a power of ln k, rising toward J for a polynomial of degree J in ln k, and rising by alpha ln 10
    per decade for c k^alpha (ln k)^beta;
(c)-(g) the pulls (n - model) / sigma of the five candidate forms, one panel per form, over the
    fitted range. Error bars are one standard error.
"""
import sys

import numpy as np

from plot_common import PAGE, SEQUENTIAL, colours, figure, legend_axes, load, save, usage

FORMS = ["power law", "a + b ln k", "a + b ln k + c (ln k)^2", "power law with log", "power of ln k"]
TEX = {"power law": r"$c\,k^\alpha$", "a + b ln k": r"$a + b \ln k$",
       "a + b ln k + c (ln k)^2": r"$a + b\ln k + c(\ln k)^2$",
       "power law with log": r"$c\,k^\alpha (\ln k)^\beta$", "power of ln k": r"$c\,(\ln k)^\beta$"}


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    fig = figure(PAGE, 5.0, nrows=0)
    grid = fig.add_gridspec(3, 1, height_ratios=[1.3, 0.4, 1])  # the middle row: the series' legend
    top, bottom = grid[0].subgridspec(1, 2), grid[2].subgridspec(1, len(FORMS))
    ax_a = fig.add_subplot(top[0])
    ax_b = fig.add_subplot(top[1])
    pulls = [fig.add_subplot(bottom[i]) for i in range(len(FORMS))]
    # One colour per series (dark to light in their order) and markers in turn, so that neighbours differ.
    palette = colours(len(data["series"]), SEQUENTIAL)
    markers = "osD^v"
    y_label = data.get("y_label", "n")
    ylab = r"$n_{\rm tot}$" if y_label == "n_tot" else r"$n_{\rm coll}$"
    for j, s in enumerate(data["series"]):
        color, marker = palette[j], markers[j % len(markers)]
        local = s.get("local", [])
        if local:
            mid = np.array([0.5 * (np.log10(l["k1"]) + np.log10(l["k2"])) for l in local])
            a = np.array([l["alpha"] for l in local], dtype=float)
            e = np.array([l["error"] for l in local], dtype=float)
            ax_a.errorbar(mid, a, yerr=e, fmt=marker + "-", ms=2.5, lw=0.8, color=color, label=s["label"])
            ln_mid = mid * np.log(10.0)
            ax_b.errorbar(mid, a * ln_mid, yerr=e * ln_mid, fmt=marker + "-", ms=2.5, lw=0.8, color=color)
        fit = s.get("fit")
        if fit:
            kf = np.log10(np.array(fit["k"], dtype=float))
            for f in fit["forms"]:
                if f["name"] in FORMS:
                    pulls[FORMS.index(f["name"])].plot(kf, f["pulls"], marker + "-", ms=2, lw=0.6, color=color)
    ax_a.set_xlabel(r"$\log_{10} k$")
    ax_a.set_ylabel(r"local exponent $d\ln %s / d\ln k$" % ylab.strip("$"))
    fig.suptitle(data.get("title", ""))
    ax_a.set_title("(a) local exponent per decade", loc="left")
    ax_b.set_xlabel(r"$\log_{10} k$")
    ax_b.set_ylabel(r"local exponent $\times \ln k$")
    ax_b.set_title(r"(b) the $\beta$ of $(\ln k)^\beta$: flat for a power of $\ln k$", loc="left")
    handles, labels = ax_a.get_legend_handles_labels()
    legend_axes(fig.add_subplot(grid[1]), handles, labels, ncol=min(4, max(1, len(labels))),
                columnspacing=1.5)
    for i, ax in enumerate(pulls):
        ax.axhline(0, color="k", lw=0.5)
        ax.axhspan(-2, 2, color="0.9")
        ax.set_xlabel(r"$\log_{10} k$")
        ax.set_title("(%s)\n%s" % ("cdefg"[i], TEX[FORMS[i]]), loc="left", fontsize=7)
    pulls[0].set_ylabel(r"pull $(n - {\rm model})/\sigma$")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
