"""Reading a granchain results store (docs/results-store.md) into numpy.

The rows are those of ``granchain export`` with the same filters: the store is opened read-only,
the C++ export's selection (src/store/store_export.hpp) reads them in one statement, and each
column comes back typed by the values the store holds: int64, float64 (NULL as nan; k = inf for
hard spheres), or str. No text lies in between.
"""

import json
import numbers

import numpy as np

from . import _granchain

TABLES = ("runs", "profiles", "collapse", "realizations")


def _values(value, name):
    """A filter as a list of floats: a number, a sequence, or the CLI's list/range text."""
    if isinstance(value, str):
        return _granchain.parse_value_list(value, "--" + name)
    if isinstance(value, numbers.Real) or np.ndim(value) == 0:
        values = [float(value)]
    else:
        values = [float(x) for x in np.asarray(value, dtype=float).ravel()]
    for x in values:
        if not np.isfinite(x):
            raise ValueError("--%s = %r: %r is not a finite number" % (name, value, x))
    return values


def _names(value):
    """Engines as a list of names: 'exact,reference' or a sequence of names."""
    if value is None:
        return []
    if isinstance(value, str):
        return _granchain.parse_name_list(value)
    return [str(v) for v in value]


def export(db, table="runs", *, N=None, e=None, k=None, T0=None, T=None, engine=None, where=None,
           as_dict=False):
    """Rows of a results store, as ``granchain export --db DB --table TABLE`` selects them.

    table: 'runs' (one row per driven-column run), 'profiles' (one row per particle of each run),
    'collapse' (one row per collapse count) or 'realizations' (one row per launch of a count).
    N, e, k, T0, T: a number, a sequence of numbers, or the CLI's list text ('0.8:0.9:0.002',
    '1e4:1e8:x10'); a row matches a value within 1e-12 relative. T0 and T do not apply to the
    collapse tables. engine: a name, 'exact,reference' or a sequence. where: an SQL condition on
    the exported columns. Filters combine with AND.

    Returns a numpy structured array (one field per column: r['n_coll'], r['T'], ...), or with
    as_dict=True a dict of column name -> numpy array. Raises ValueError for a missing or foreign
    store, a bad filter or a bad where (the CLI's message).
    """
    if table not in TABLES:
        raise ValueError(f"--table = '{table}' is not a table; valid: {', '.join(TABLES)}")
    values = {}
    for name, v in (("N", N), ("e", e), ("k", k), ("T0", T0), ("T", T)):
        if v is not None:
            values[name] = _values(v, name)
    columns = dict(_granchain._read_columns(db, table, values, _names(engine), where or ""))
    if as_dict:
        return columns
    rows = len(next(iter(columns.values()))) if columns else 0
    out = np.empty(rows, dtype=[(name, a.dtype) for name, a in columns.items()])
    for name, a in columns.items():
        out[name] = a
    return out


def analyze(db, *, N=None, e=None, k=None, T0=None, T=None, engine=None, k_min=0.0):
    """The analysis of ``granchain analyze --db DB --json`` (docs/analysis.md), as a dict.

    N, e, k, T0, T: the runs analysed, each a number, a sequence or the CLI's list text (k =
    '1e6:1e10:x10' fits one window of k); engine: a name or a sequence; k_min: only k >= k_min
    enters the fits. Keys: 'families' (per engine, N, T0: 'curves' with n_coll(k), the
    regime, log and power fits, curvature, local exponents and the partially condensed state at
    the largest k; e_c1 with its estimate and classification boundary, both readings of e_c2, the
    mean exponent alpha_bar and its local exponents, the replica check), 'across_N' (the fits
    (1 - e_c) = A/N and alpha_bar against log10 N), 'runs', 'k_min'. Critical values not found are
    None. Raises ValueError for a missing or foreign store or a bad filter.
    """
    values = {}
    for name, v in (("N", N), ("e", e), ("k", k), ("T0", T0), ("T", T)):
        if v is not None:
            values[name] = _values(v, name)
    return json.loads(_granchain._analyze_text(db, values, _names(engine), float(k_min)))


# Store's rows as a notebook reads them (export() keeps the CLI's columns): the names the results of
# run() use (SQL column names ignore case, so the store calls K "K_mean" beside k and D
# "damping_D" beside d), verdicts as booleans, creation times as datetime64, rows sorted by the
# parameters (as the sweep's table lists them) rather than by when they were stored.
_RENAMED = {"K_mean": "K", "damping_D": "D"}
_BOOLEAN = {"runs": ("n_coll_converged", "stationary"), "realizations": ("collapsed",)}
_ORDER = {
    "runs": ("engine", "N", "T0", "k", "T", "e", "seed", "id"),
    "profiles": ("engine", "N", "T0", "k", "T", "e", "seed", "run_id", "i"),
    "collapse": ("setup", "engine", "N", "e", "k", "seed", "id"),
    "realizations": ("setup", "engine", "N", "e", "k", "seed", "run_id", "realization"),
}


def _notebook_rows(rows, table):
    names = [_RENAMED.get(n, n) for n in rows.dtype.names]
    columns = {}
    for old, new in zip(rows.dtype.names, names):
        a = rows[old]
        if old in _BOOLEAN.get(table, ()) and a.dtype.kind in "iu":
            a = a.astype(bool)  # (a column with NULLs, read as float with nan, stays as it is)
        elif old == "created_utc" and a.dtype.kind == "U":
            a = np.array([t.rstrip("Z") for t in a], dtype="datetime64[s]")
        columns[new] = a
    out = np.empty(len(rows), dtype=[(n, a.dtype) for n, a in columns.items()])
    for n, a in columns.items():
        out[n] = a
    keys = [out[k] for k in reversed(_ORDER[table]) if k in columns]
    return out[np.lexsort(keys)] if keys and len(out) else out


class Store:
    """A results store opened for reading: Store('granchain.db').runs(N=25, e=0.9).

    Its tables come back as numpy structured arrays sorted by the parameters, with the names of
    run()'s results (K, D), booleans and datetime64 creation times; export() gives the rows as
    ``granchain export`` does."""

    def __init__(self, path):
        self.path = _granchain._check_store(path)  # ValueError if it is not a readable store

    def analyze(self, **filters):
        """The analysis of its driven-column runs: analyze(db, N=, e=, k=, T0=, T=, engine=, k_min=)."""
        return analyze(self.path, **filters)

    def runs(self, **filters):
        """Driven-column runs: parameters, n_coll, rates with errors, verdicts, cost, point key, replica."""
        return _notebook_rows(export(self.path, "runs", **filters), "runs")

    def profiles(self, **filters):
        """Per-particle profiles (z_mean, z_std, K with errors) beside each run's parameters."""
        return _notebook_rows(export(self.path, "profiles", **filters), "profiles")

    def collapse(self, **filters):
        """Collapse counts: one row per (e, k) point with n_tot and its error."""
        return _notebook_rows(export(self.path, "collapse", **filters), "collapse")

    def realizations(self, **filters):
        """Per-launch counts of every collapse count."""
        return _notebook_rows(export(self.path, "realizations", **filters), "realizations")

    def __repr__(self):
        return f"granchain.Store({self.path!r})"
