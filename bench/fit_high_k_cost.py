#!/usr/bin/python3
"""The exact engine's cost model above k = 1e10 (src/sweep/cost_model.cpp) against the stored runs,
and the growth per decade of k that it fits.

Inside its box (k <= 1e10) the model is a fit of ln(seconds per unit time); above it, it multiplies
the rate at k = 1e10 by exp(s (log10 k - 10)), where
    s(N, e) = P(x) + delta w(c) ln(max(N, 100) / 100),   c = N (1 - e), x = ln(1 + c),
P piecewise linear in x between its values at the knots c = KNOTS_C (x clamped to the first and
last: flat beyond c = 35, the columns of N = 50 ... 300 on the power-law side, which grow alike),
w = 1 for c <= 3, falling linearly to 0 at c = 5: an uncollapsing large column's cost falls more
slowly than a small one's (about -0.1 per decade at N <= 100, -0.05 at N = 300 and 500, none at
1000). A falling rate (s < 0) is followed only over the FALL_DECADES decades measured. A collapsing
column's collision rate per particle grows like k^alpha (the paper's power-law regime), and so does
the number of events; an uncollapsing one's hardly grows.

    /usr/bin/python3 bench/fit_high_k_cost.py STORE [STORE ...] [--granchain build/granchain]

For every exact-engine run on the thermal floor with a stored CPU time at k >= 1e10: the binary's
prediction (`granchain sweep --dry-run` of the run's point, matched by seed), the term above divided
out again (S_NOW below, keep in step with kAboveKKnots and kAboveKLargeN), and the least-squares fit of
    ln(measured / predicted at k = 1e10's rate) = u_column + s(N, e) (log10 k - 10),
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

KNOTS_C = (1.2, 2.0, 2.8, 3.5, 5.0, 10.0, 35.0)  # kAboveKKnotsC in src/sweep/cost_model.cpp
KNOTS_X = tuple(math.log1p(c) for c in KNOTS_C)
S_NOW = ((-0.093, -0.092, -0.096, 0.006, 0.081, 0.520, 0.458), 0.033)  # kAboveKKnots, kAboveKLargeN
FALL_DECADES = 5  # kDecadesOfFallMeasured: the uncollapsing columns' runs reach k = 1e15
CLASSES = ((0.0, 3.0), (3.0, 6.0), (6.0, 30.0), (30.0, 1e9))  # of N (1 - e), for the tables


def class_of(c):
    """The index in CLASSES of N (1 - e) = c."""
    return next(i for i, (lo, hi) in enumerate(CLASSES) if lo <= c < hi)


def class_label(cls):
    lo, hi = CLASSES[cls]
    return "%g - %g" % (lo, hi) if hi < 1e9 else ">= %g" % lo


def hats(N, e):
    """The weights of P's knots at N (1 - e): P(x) = hats . knots."""
    x = min(max(math.log1p(N * (1.0 - e)), KNOTS_X[0]), KNOTS_X[-1])
    v = np.zeros(len(KNOTS_X))
    for j in range(len(KNOTS_X) - 1):
        if KNOTS_X[j] <= x <= KNOTS_X[j + 1]:
            t = (x - KNOTS_X[j]) / (KNOTS_X[j + 1] - KNOTS_X[j])
            v[j], v[j + 1] = 1.0 - t, t
            break
    return v


def large_n(N, e):
    """w(c) ln(max(N, 100) / 100): where and by how much a large column's fall is slower."""
    c = N * (1.0 - e)
    w = 1.0 if c <= 3.0 else 0.0 if c >= 5.0 else (5.0 - c) / 2.0
    return w * math.log(max(N, 100.0) / 100.0)


def slope(s, N, e):
    knots, delta = s
    return float(hats(N, e) @ np.array(knots)) + delta * large_n(N, e)


def log_growth(s, N, e, lk):
    """ln of the rate's gain from k = 1e10 to lk decades above it; a fall stops after FALL_DECADES."""
    g = slope(s, N, e)
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


def s_now_mismatch(granchain):
    """Where S_NOW's growth per decade differs from the binary's (its --dry-run cost at k = 1e15
    against 1e10, over the five decades a fall is followed) by more than 0.002; '' where it does not."""
    out = []
    for N, c in ((10, 1.2), (100, 2.8), (300, 2.5), (300, 6.0), (1000, 1.2), (1000, 4.0), (100, 70.0)):
        e = repr(1.0 - c / N)
        args = [granchain, "sweep", "--N", str(N), "--e", e, "--k", "1e10,1e15", "--T", "1e6",
                "--db", "/nonexistent/none.db", "--dry-run"]
        text = subprocess.run(args, check=True, capture_output=True, text=True).stdout
        cost = {float(line.split("k=")[1].split()[0]): float(line.split()[1]) for line in text.splitlines() if "driven_column" in line}
        binary = math.log(cost[1e15] / cost[1e10]) / 5.0
        if abs(binary - slope(S_NOW, N, float(e))) > 0.002:
            out.append("N = %d, c = %g: binary %.4f, S_NOW %.4f" % (N, c, binary, slope(S_NOW, N, float(e))))
    return "; ".join(out)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("stores", nargs="+")
    ap.add_argument("--granchain", default="build/granchain")
    a = ap.parse_args(argv[1:])
    mismatch = s_now_mismatch(a.granchain)
    if mismatch:
        sys.stderr.write("S_NOW is not the binary's growth above k = 1e10 (keep it in step with src/sweep/cost_model.cpp): %s\n"
                         % mismatch)
        return 2
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
    nk = len(KNOTS_X)
    # A falling column's decades stop at FALL_DECADES, as in the model: which columns fall depends
    # on the fit, so it is repeated until that set no longer changes.
    s, falling = S_NOW, None
    for _ in range(20):
        now_falling = {c for c in fit_cols if slope(s, c[0], c[1]) < 0}
        if now_falling == falling:
            break
        falling = now_falling
        A = np.zeros((len(used), len(fit_cols) + nk + 1))
        b = np.zeros(len(used))
        for row, i in enumerate(used):
            N, e, T0, lk, _y, y0 = data[i]
            d = min(lk, FALL_DECADES) if (N, e, T0) in falling else lk
            A[row, fit_cols.index((N, e, T0))] = 1.0
            A[row, len(fit_cols):len(fit_cols) + nk] = d * hats(N, e)
            A[row, -1] = d * large_n(N, e)
            b[row] = y0
        coef, *_ = np.linalg.lstsq(A, b, rcond=None)
        s = (tuple(coef[len(fit_cols):len(fit_cols) + nk]), coef[-1])
    res = b - A @ coef
    print("fit over %d runs of %d columns: P at N (1 - e) = %s; delta = %.4f; residual rms %.3f in ln"
          % (len(used), len(fit_cols), ", ".join("%g: %.3f" % kv for kv in zip(KNOTS_C, s[0])), s[1], res.std()))
    print("  as C++: constexpr double kAboveKKnots[%d] = {%s}; kAboveKLargeN = %.3f;"
          % (nk, ", ".join("%.3f" % v for v in s[0]), s[1]))
    print("  s at N (1 - e) = 1.2 for N = 100, 300, 1000: " + ", ".join("%.3f" % slope(s, N, 1.0 - 1.2 / N) for N in (100, 300, 1000)))

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
