#!/usr/bin/python3
"""The exact engine's cost model above k = 1e10 (src/sweep/cost_model.cpp) against the stored runs,
and the growth per decade of k that it fits.

Inside its box (k <= 1e10) the model is a fit of ln(seconds per unit time); above it, it multiplies
the rate at k = 1e10 by exp(s(x) (log10 k - 10)), x = ln(1 + N (1 - e)), where
    s(x) = s0 + s1 x + s2 x^2,   x clamped to [X_MIN, X_MAX],
a falling rate (s < 0) only over the FALL_DECADES decades measured. X_MIN is the runs' smallest
N (1 - e); above X_MAX (N (1 - e) = 35, the columns of N = 50 ... 300 on the power-law side) s is
flat: those columns grow alike (0.42 ... 0.68 each) and a polynomial through them would bend.
A collapsing column's collision rate per particle grows like k^alpha (the paper's power-law regime),
and so does the number of events; an uncollapsing one's hardly grows: s runs from about -0.17 at
N (1 - e) = 1.2 to about 0.6 at N (1 - e) >= 35.

    /usr/bin/python3 bench/fit_high_k_cost.py STORE [STORE ...] [--granchain build/granchain]

For every exact-engine run on the thermal floor with a stored CPU time at k >= 1e10: the binary's
prediction (`granchain sweep --dry-run` of the run's point, matched by seed), the term above divided
out again (S_NOW below, keep in step with kAboveKCoefficients), and the least-squares fit of
    ln(measured / predicted at k = 1e10's rate) = u_column + s(x) (log10 k - 10),
u_column one free offset per column (N, e, k_B T0): the box's own error at that column, which the
term above k = 1e10 should not absorb. Columns with a single k carry no slope and are left out of
the fit. Prints the coefficients, then measured / predicted per class of N (1 - e) and decade of k
with the binary's model and with k held at 1e10 (geometric mean and the share within a factor of 2).
"""
import argparse
import collections
import math
import sqlite3
import subprocess
import sys

import numpy as np

S_NOW = (-0.374, 0.255, 0.005)  # kAboveKCoefficients in src/sweep/cost_model.cpp
X_MIN, X_MAX = math.log1p(1.2), math.log1p(35.0)
FALL_DECADES = 5  # kDecadesOfFallMeasured: the uncollapsing columns' runs reach k = 1e15
CLASSES = ((0.0, 3.0), (3.0, 6.0), (6.0, 30.0), (30.0, 1e9))  # of N (1 - e), for the tables


def class_of(c):
    """The index in CLASSES of N (1 - e) = c."""
    return next(i for i, (lo, hi) in enumerate(CLASSES) if lo <= c < hi)


def class_label(cls):
    lo, hi = CLASSES[cls]
    return "%g - %g" % (lo, hi) if hi < 1e9 else ">= %g" % lo


def clamp_x(N, e):
    return min(max(math.log1p(N * (1.0 - e)), X_MIN), X_MAX)


def slope(s, x):
    return s[0] + s[1] * x + s[2] * x * x


def log_growth(s, N, e, lk):
    """ln of the rate's gain from k = 1e10 to lk decades above it; a fall stops after FALL_DECADES."""
    g = slope(s, clamp_x(N, e))
    return g * (min(lk, FALL_DECADES) if g < 0 else lk)


def stored_runs(path):
    con = sqlite3.connect("file:%s?mode=ro" % path, uri=True)
    q = """SELECT r.N, r.e, r.k, r.T0, r.T, r.transient, r.seed, r.cpu_seconds, coalesce(p.replica, 0)
           FROM runs r LEFT JOIN run_points p ON p.run_id = r.id
           WHERE r.engine = 'exact' AND r.setup = 'driven_column' AND coalesce(r.drive, 'thermal') = 'thermal'
             AND r.cpu_seconds IS NOT NULL AND r.k >= 1e10 * (1 - 1e-9)"""
    return con.execute(q).fetchall()


def predictions(granchain, rows):
    """seed -> the binary's predicted seconds, from one dry run per (N, T0, T, transient)."""
    groups = collections.defaultdict(lambda: [set(), set(), 0])
    for N, e, k, T0, T, tr, seed, cpu, rep in rows:
        g = groups[(N, T0, T, tr)]
        g[0].add(repr(e))
        g[1].add(repr(k))
        g[2] = max(g[2], rep + 1)
    out = {}
    for (N, T0, T, tr), (es, ks, reps) in groups.items():
        args = [granchain, "sweep", "--N", str(N), "--e", ",".join(sorted(es)), "--k", ",".join(sorted(ks)),
                "--T0", repr(T0), "--T", repr(T), "--transient", repr(tr), "--replicas", str(reps),
                "--db", "/nonexistent/none.db", "--dry-run"]
        text = subprocess.run(args, check=True, capture_output=True, text=True).stdout
        for line in text.splitlines():
            if "driven_column" in line:
                f = line.split()
                out[int(f[3])] = float(f[1])
    return out


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("stores", nargs="+")
    ap.add_argument("--granchain", default="build/granchain")
    a = ap.parse_args(argv[1:])
    rows = [r for path in a.stores for r in stored_runs(path)]
    pred = predictions(a.granchain, rows)
    data = []  # N, e, T0, lk, ln(measured / predicted), that with today's term above 1e10 divided out
    for N, e, k, T0, T, tr, seed, cpu, rep in rows:
        if seed in pred and cpu > 0:
            lk = max(math.log10(k) - 10.0, 0.0)
            y = math.log(cpu / pred[seed])
            data.append((N, e, T0, lk, y, y + log_growth(S_NOW, N, e, lk)))
    if not data:
        sys.stderr.write("no exact-engine run at k >= 1e10 with a CPU time in %s\n" % ", ".join(a.stores))
        return 2
    print("%d runs at k >= 1e10 matched by seed (of %d stored)" % (len(data), len(rows)))

    columns = collections.defaultdict(list)
    for i, (N, e, T0, lk, *_r) in enumerate(data):
        columns[(N, e, T0)].append(i)
    fit_cols = [c for c, idx in columns.items() if len({data[i][3] for i in idx}) >= 2]
    used = [i for c in fit_cols for i in columns[c]]
    A = np.zeros((len(used), len(fit_cols) + 3))
    b = np.zeros(len(used))
    for row, i in enumerate(used):
        N, e, T0, lk, _y, y0 = data[i]
        A[row, fit_cols.index((N, e, T0))] = 1.0
        x = clamp_x(N, e)
        A[row, -3:] = (lk, lk * x, lk * x * x)
        b[row] = y0
    coef, *_ = np.linalg.lstsq(A, b, rcond=None)
    s = coef[-3:]
    res = b - A @ coef
    print("fit over %d runs of %d columns: s(x) = %.3f + %.3f x + %.3f x^2, x = ln(1 + N (1 - e)) in [%.2f, %.2f]; "
          "residual rms %.2f in ln" % (len(used), len(fit_cols), s[0], s[1], s[2], X_MIN, X_MAX, res.std()))
    print("  as C++: constexpr double kAboveKCoefficients[3] = {%.3f, %.3f, %.3f};" % tuple(s))
    print("  s at N (1 - e) = " + ", ".join("%g: %.3f" % (c, slope(s, clamp_x(c + 1, 1.0 / (c + 1))))
                                             for c in (1.2, 2.6, 5, 10, 35, 135, 300)))

    print("\nmeasured / predicted (geometric mean, share within 2x) by N (1 - e) and k, with the binary's model and with")
    print("k held at 1e10 (the term above divided out):")
    print("%-14s %8s %6s %10s %10s %12s %10s" % ("N (1 - e)", "k", "runs", "geo mean", "within 2x", "held: geo", "within 2x"))
    cells = collections.defaultdict(list)
    for N, e, T0, lk, y, y0 in data:
        c = N * (1.0 - e)
        cls = class_of(c)
        cells[(cls, round(lk))].append((y, y0))
    within = lambda v: 100.0 * np.mean(np.abs(v) < math.log(2.0))

    def print_row(cls, k_text, pairs):
        lo, hi = CLASSES[cls]
        label = "%g - %g" % (lo, hi) if hi < 1e9 else ">= %g" % lo
        ys, y0s = np.array(pairs).T
        print("%-14s %8s %6d %10.2f %9.0f %% %12.2f %9.0f %%" % (label, k_text, len(ys), math.exp(ys.mean()), within(ys),
                                                            math.exp(y0s.mean()), within(y0s)))

    for (cls, lk), pairs in sorted(cells.items()):
        print_row(cls, "1e%d" % (10 + lk), pairs)
    print("\nper N (1 - e), all k above 1e10:")
    for cls in range(len(CLASSES)):
        pairs = [p for (c, lk), v in cells.items() if c == cls and lk > 0 for p in v]
        if pairs:
            print_row(cls, "> 1e10", pairs)
    ys = np.array([d[4] for d in data if d[3] > 0.5])
    ys0 = np.array([d[5] for d in data if d[3] > 0.5])
    print("above k = 1e10: %d runs, within 2x %.0f %% (with k held at 1e10: %.0f %%), geometric mean %.2f (%.2f)"
          % (len(ys), within(ys), within(ys0), math.exp(ys.mean()), math.exp(ys0.mean())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
