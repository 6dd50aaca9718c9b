#!/usr/bin/python3
"""Redraws panel (a) of the paper's Fig. cfreqlogN25 (n_coll against log10 k, one curve per e,
N = 25) from a results store, through the Python module granchain; no simulation is run.

    PYTHONPATH=build/python /usr/bin/python3 examples/redraw_fig5_from_store.py \
        [--db data/quick/quick.db] [--N 25] [--T0 1] [--e 0.80:0.90:0.01] [--out fig5_from_store.png]

Runs of one (e, k) stored more than once (replicas) are averaged, their errors combined as
independent. Error bars are one standard error. Prints the file written.
"""
import argparse
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
try:
    import granchain
except ImportError:  # run without PYTHONPATH: the module of the default build folder
    sys.path.insert(0, str(ROOT / "build" / "python"))
    import granchain

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def points(rows):
    """(e, k) -> (n_coll, error): replicas averaged, errors combined as independent."""
    out = {}
    for e, k in sorted(set(zip(rows["e"].tolist(), rows["k"].tolist()))):
        sel = (rows["e"] == e) & (rows["k"] == k)
        n, err = rows["n_coll"][sel], rows["n_coll_err"][sel]
        out[(e, k)] = (n.mean(), np.sqrt(np.sum(err**2)) / len(n))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--db", default=str(ROOT / "data" / "quick" / "quick.db"), help="results store to read")
    ap.add_argument("--N", type=int, default=25, help="number of particles (default 25)")
    ap.add_argument("--T0", type=float, default=1.0, help="floor temperature (default 1)")
    ap.add_argument("--engine", default="exact", help="engine of the runs (default exact)")
    ap.add_argument("--e", default="0.80:0.90:0.01", help="restitution coefficients, the CLI's list syntax "
                    "(default 0.80:0.90:0.01, the paper's panel)")
    ap.add_argument("--out", default="fig5_from_store.png", help="PNG to write (default fig5_from_store.png)")
    a = ap.parse_args()

    rows = granchain.Store(a.db).runs(N=a.N, T0=a.T0, engine=a.engine, e=a.e)
    rows = rows[np.isfinite(rows["k"])]  # hard-sphere runs (k = inf) have no place on a log k axis
    if len(rows) == 0:
        sys.exit(f"no runs with N = {a.N}, T0 = {a.T0:g}, engine {a.engine}, e in {a.e} in {a.db}")
    pts = points(rows)
    es = sorted({e for e, _ in pts})

    fig, ax = plt.subplots(figsize=(6, 4.5))
    cmap = plt.get_cmap("viridis")
    norm = plt.Normalize(min(es), max(es) if max(es) > min(es) else min(es) + 1e-9)
    for e in es:
        ks = sorted(k for ee, k in pts if ee == e)
        n, s = np.array([pts[(e, k)] for k in ks]).T
        ax.errorbar(np.log10(ks), n, yerr=s, fmt="o-", ms=3, lw=0.8, capsize=2, color=cmap(norm(e)))
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label="e")
    ax.set_xlabel("log10 k")
    ax.set_ylabel("n_coll")
    ax.set_title(f"N = {a.N}, T0 = {a.T0:g}, {a.engine} engine ({len(rows)} runs, {pathlib.Path(a.db).name})")
    fig.tight_layout()
    fig.savefig(a.out, dpi=150)
    print(f"wrote {a.out}: {len(es)} values of e, {len(pts)} points from {len(rows)} runs")


if __name__ == "__main__":
    main()
