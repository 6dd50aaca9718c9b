"""Reading a granchain results store (docs/results-store.md) into numpy.

The rows are those of ``granchain export`` with the same filters: the store is opened read-only
and the C++ export (src/store/store_export.hpp) selects them. Its JSON form tells each column's
type (integer, real or text) and its CSV form carries every real exactly, infinities included
(k = inf for hard spheres), so a column comes back as int64, float64 (NULL as nan), or str.
"""

import csv
import io
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


def _column(name, json_rows, csv_rows, j):
    """One column as a numpy array, typed by the JSON values, reals read from the CSV text."""
    vals = [row[name] for row in json_rows]
    kinds = {type(v) for v in vals if v is not None}
    if str in kinds:
        return np.array(["" if v is None else str(v) for v in vals], dtype=str)
    if float in kinds:
        return np.array([float(r[j]) if r[j] != "" else np.nan for r in csv_rows], dtype=float)
    if kinds == {int}:
        if None not in vals:
            return np.array(vals, dtype=np.int64)
        if all(v is None or abs(v) < 2**53 for v in vals):
            return np.array([np.nan if v is None else float(v) for v in vals], dtype=float)
        return np.array(vals, dtype=object)  # large integers with NULLs: exact, None for NULL
    return np.full(len(vals), np.nan)  # all NULL (or no rows)


def _read(db, table, values, engines, where):
    for _ in range(3):
        rows = json.loads(_granchain._export_text(db, table, "json", values, engines, where))
        reader = csv.reader(io.StringIO(_granchain._export_text(db, table, "csv", values, engines, where)))
        header = next(reader)
        # Rows stored between the two reads come last (ordered by id); they are left out.
        body = [r for _, r in zip(range(len(rows)), reader)]
        key = header[0]
        if len(body) == len(rows) and all(str(a[key]) == b[0] for a, b in zip(rows, body)):
            return header, rows, body
    raise RuntimeError(f"the store {db} kept changing while it was read; try again")


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
    header, rows, body = _read(db, table, values, _names(engine), where or "")
    columns = {name: _column(name, rows, body, j) for j, name in enumerate(header)}
    if as_dict:
        return columns
    out = np.empty(len(rows), dtype=[(name, a.dtype) for name, a in columns.items()])
    for name, a in columns.items():
        out[name] = a
    return out


def analyze(db, *, N=None, T0=None, engine=None, k_min=0.0):
    """The analysis of ``granchain analyze --db DB --json`` (docs/analysis.md), as a dict.

    N, T0: a number, a sequence or the CLI's list text; engine: a name or a sequence; k_min: only
    k >= k_min enters the fits. Keys: 'families' (per engine, N, T0: 'curves' with n_coll(k), the
    regime, log and power fits, curvature, local exponents and the partially condensed state at
    the largest k; e_c1 with its estimate and classification boundary, both readings of e_c2, the
    mean exponent alpha_bar and its local exponents, the replica check), 'across_N' (the fits
    (1 - e_c) = A/N and alpha_bar against log10 N), 'runs', 'k_min'. Critical values not found are
    None. Raises ValueError for a missing or foreign store or a bad filter.
    """
    values = {}
    for name, v in (("N", N), ("T0", T0)):
        if v is not None:
            values[name] = _values(v, name)
    return json.loads(_granchain._analyze_text(db, values, _names(engine), float(k_min)))


class Store:
    """A results store opened for reading: Store('granchain.db').runs(N=25, e=0.9)."""

    def __init__(self, path):
        self.path = _granchain._check_store(path)  # ValueError if it is not a readable store

    def analyze(self, **filters):
        """The analysis of its driven-column runs: analyze(db, N=, T0=, engine=, k_min=)."""
        return analyze(self.path, **filters)

    def runs(self, **filters):
        """Driven-column runs: parameters, n_coll, rates with errors, cost, point key, replica."""
        return export(self.path, "runs", **filters)

    def profiles(self, **filters):
        """Per-particle profiles (z_mean, z_std, K_mean with errors) beside each run's parameters."""
        return export(self.path, "profiles", **filters)

    def collapse(self, **filters):
        """Collapse counts: one row per (e, k) point with n_tot and its error."""
        return export(self.path, "collapse", **filters)

    def realizations(self, **filters):
        """Per-launch counts of every collapse count."""
        return export(self.path, "realizations", **filters)

    def __repr__(self):
        return f"granchain.Store({self.path!r})"
