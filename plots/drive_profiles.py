#!/usr/bin/python3
"""The classical observables of the vibrated column from `granchain reproduce --figure drives-profiles`
(drives-profiles.json).

Usage: /usr/bin/python3 plots/drive_profiles.py drives-profiles.json PREFIX   -> PREFIX.png and PREFIX.pdf
One row per N(1 - e) (a fluidised and a condensed column), one colour per drive: (a) the number
density n(z) against height z (particles per d), (b) the granular temperature T(z) = m<(v - u)^2>
of the particles at height z (k_B T0 = 1), both with batch-means error bars where they exceed the
line width; (c) the centre of mass z_cm - <z_cm> through the plate's cycle, the plate's surface
dashed; (d) the centre of mass's velocity, the plate's dashed.
"""
import sys

import numpy as np

from plot_common import PAGE, figure, legend_axes, load, plt, save, usage

COLOURS = {"thermal": "#222222", "sine": "#1f4e9c", "sawtooth": "#c0392b", "quadratic": "#2a9d8f"}


def series(d):
    v = np.array([np.nan if x is None else x for x in d["value"]], dtype=float)
    e = np.array([np.nan if x is None else x for x in d["error"]], dtype=float)
    return v, e


def main(argv):
    if usage(__doc__, argv, 2):
        return 2
    data = load(argv[1])
    cs = sorted({c["c"] for c in data["columns"]})
    fig, axes = figure(PAGE, 2.0 * len(cs) + 0.4, nrows=len(cs), ncols=5, gridspec_kw={"width_ratios": [1, 1, 1, 1, 0.55]},
                       squeeze=False)
    handles, labels = {}, {}
    for row, c in enumerate(cs):
        a_n, a_t, a_z, a_v, lax = axes[row]
        lax.set_axis_off()
        for col in (x for x in data["columns"] if x["c"] == c):
            colour = COLOURS.get(col["drive"], "0.3")
            z = np.array(col["z"])
            n, n_err = series(col["density"])
            t, t_err = series(col["temperature"])
            line, = a_n.plot(z, n, color=colour, lw=0.9)
            a_n.fill_between(z, n - n_err, n + n_err, color=colour, alpha=0.2, lw=0)
            a_t.plot(z, t, color=colour, lw=0.9)
            a_t.fill_between(z, t - t_err, t + t_err, color=colour, alpha=0.2, lw=0)
            handles[col["drive"]] = line
            labels[col["drive"]] = col["drive"]
            ph = col.get("phase")
            if ph:
                th = np.degrees(np.array(ph["theta"]))
                zc, zc_err = series(ph["z_cm"])
                vc, vc_err = series(ph["v_cm"])
                zp, _ = series(ph["z_plate"])
                vp, _ = series(ph["v_plate"])
                a_z.errorbar(th, zc - np.nanmean(zc), yerr=zc_err, color=colour, lw=0.9, ms=2, fmt="o-", capsize=1)
                a_z.plot(th, zp - np.nanmean(zp), color=colour, ls="--", lw=0.7)
                a_v.errorbar(th, vc, yerr=vc_err, color=colour, lw=0.9, ms=2, fmt="o-", capsize=1)
                a_v.plot(th, vp, color=colour, ls="--", lw=0.7)
        a_n.set_ylabel(r"$n(z)$ [1/$d$]")
        a_t.set_ylabel(r"$T(z)$ [$k_B T_0$]")
        a_z.set_ylabel(r"$z_{cm} - \langle z_{cm} \rangle$ [$d$]")
        a_v.set_ylabel(r"$v_{cm}$")
        a_n.set_title(r"$N(1-e)$ = %g: (a) density" % c, loc="left")
        a_t.set_title("(b) temperature", loc="left")
        a_z.set_title("(c) centre of mass", loc="left")
        a_v.set_title("(d) its velocity", loc="left")
        a_t.set_yscale("log")
        for ax in (a_n, a_t):
            ax.set_xlabel(r"$z$ [$d$]")
            ax.set_xlim(left=0)
        for ax in (a_z, a_v):
            ax.set_xlabel(r"plate phase $\theta$ [deg]")
            ax.set_xlim(0, 360)
            ax.set_xticks([0, 90, 180, 270, 360])
    names = list(handles)
    extra = [plt.Line2D([], [], color="0.3", ls="--", lw=0.7)]
    legend_axes(axes[0][4], [handles[n] for n in names] + extra, [labels[n] for n in names] + ["plate"], loc="center left")
    save(fig, argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
