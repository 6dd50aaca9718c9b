#!/usr/bin/python3
"""The paper's Figs. cflogk (fig3) and cfe (fig4), N = 3 ... 6, from the JSON that `granchain
reproduce --figure fig3` or `fig4` writes (the analysis of their common sweep; "figure" names which).

Usage: /usr/bin/python3 plots/small_n.py fig3.json PREFIX   -> PREFIX.png and PREFIX.pdf
One panel per N, page wide:
cflogk: n_coll against log10 k, one colour per e (colour bar), with the fitted a + b log10 k of the
        logarithmically collapsing curves;
cfe:    n_coll against e, one curve per k (legend), with the free-space critical values
        e_c(3) ... e_c(N + 1) (dotted), e_c1 with its error, the classification boundary and the
        e_c2 bracket (bands).
Error bars are one standard error; crosses: a run whose window was not stationary.
"""
import sys

from ncoll_panels import against_e, against_log_k, e_colorbar, e_norm
from plot_common import PAGE, figure, legend_axes, load, save, usage


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    families = sorted((f for f in data["families"] if any(c["n_coll_of_k"] for c in f["curves"])), key=lambda f: f["N"])
    if not families:
        raise SystemExit("no curve to draw")
    log_k = data["figure"] == "cflogk"
    rows = (len(families) + 1) // 2
    if log_k:
        fig, axes = figure(PAGE, 2.3 * rows + 0.3, nrows=rows, ncols=2, squeeze=False)
    else:  # a row below for the legend of k and the critical values
        fig, axes = figure(PAGE, 2.3 * rows + 0.6, nrows=rows + 1, ncols=2, squeeze=False,
                           gridspec_kw={"height_ratios": [1] * rows + [0.22]})
    panels = [ax for row in axes[:rows] for ax in row]
    norm = e_norm([c for f in families for c in f["curves"]])
    handles, labels = [], []
    for i, (ax, f) in enumerate(zip(panels, families)):
        curves = [c for c in f["curves"] if c["n_coll_of_k"]]
        title = "(%s) $N = %d$" % ("abcdefgh"[i], f["N"])
        if log_k:
            against_log_k(ax, curves, data.get("k_min", 0.0), False, title, norm)
        else:
            h, l = against_e(ax, f, curves)
            ax.set_title(title, loc="left")
            for handle, label in zip(h, l):
                if label not in labels:
                    handles.append(handle)
                    labels.append(label)
    for ax in panels[len(families):]:
        ax.set_axis_off()
    if log_k:
        for ax in panels[1:len(families):2]:  # one colour bar per row, right of its last panel
            e_colorbar(fig, ax, norm)
        fig.suptitle(r"$n_{\rm coll}$ against $\log_{10} k$, $k_B T_0 = 1$ (lines: fits $a + b \log_{10} k$ of "
                     r"logarithmically collapsing $e$)")
    else:
        for ax in axes[rows]:
            ax.remove()
        legend_axes(fig.add_subplot(fig.axes[0].get_gridspec()[rows, :]), handles, labels, ncol=4, columnspacing=1.2)
        fig.suptitle(r"$n_{\rm coll}$ against $e$, $k_B T_0 = 1$")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
