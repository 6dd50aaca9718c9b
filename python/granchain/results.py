"""What run(), collapse(), trace() and sweep() return: dicts with attribute access, a short repr
and the conversions a notebook expects (numpy structured arrays; pandas DataFrames where Debian's
python3-pandas is installed).

Every result is a dict (r["n_coll"] and r.n_coll are the same value; nested dicts likewise:
r.parameters.N), so code written for plain dicts keeps working; its repr names the point and the
main number with its error instead of printing every array and the JSON text.
"""

import re
import warnings

import numpy as np

from . import _granchain


class QualityWarning(UserWarning):
    """A verdict on a result that its reader must see: a window that is not stationary, an error
    bar whose blocking analysis found no plateau (the texts of ``granchain run``'s warnings)."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (KeyboardInterrupt) during collapse(), trace() or sweep(): ``result`` holds what
    finished (a collapse count over the launches done, the samples recorded, the sweep's finished
    points — stored already where a store was given)."""

    def __init__(self, result, what):
        super().__init__(f"interrupted: {what}; the part that finished is this exception's .result")
        self.result = result


def _pandas(what):
    try:
        import pandas
    except ImportError as err:  # pragma: no cover - depends on the machine
        raise ImportError(f"{what} needs pandas (Debian: apt install python3-pandas)") from err
    return pandas


def _short(value):
    """A value as a repr shows it: numbers in %g, arrays by their shape."""
    if isinstance(value, (bool, np.bool_)):
        return repr(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.6g}"
    if isinstance(value, np.ndarray):
        return f"<array {value.dtype} {value.shape}>"
    if isinstance(value, str):
        return repr(value) if len(value) <= 40 else f"<text of {len(value)} characters>"
    if isinstance(value, dict):
        return "{...}"
    return repr(value)


def _with_error(value, error):
    return _granchain._format_with_error(float(value), float("nan") if error is None else float(error))


class Record(dict):
    """A dict whose keys are also attributes (r.n_coll is r["n_coll"]), nested dicts likewise."""

    def __init__(self, data=(), **more):
        super().__init__(data, **more)
        for key, value in self.items():
            if isinstance(value, dict) and not isinstance(value, Record):
                dict.__setitem__(self, key, Record(value))

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(f"{type(self).__name__} has no field {name!r}; fields: {', '.join(self)}") from None

    def __dir__(self):
        return sorted(set(super().__dir__()) | {k for k in self if isinstance(k, str) and k.isidentifier()})

    def to_dict(self):
        """A plain dict (nested records as plain dicts)."""
        return {k: v.to_dict() if isinstance(v, Record) else v for k, v in self.items()}

    def __repr__(self):
        return type(self).__name__ + "(" + ", ".join(f"{k}={_short(v)}" for k, v in self.items()) + ")"

    def _repr_pretty_(self, printer, cycle):  # IPython shows the same short repr
        printer.text(repr(self))


def _point(p, names):
    """name=value for the names p holds, those that are None (a plate's A under the thermal floor) left out."""
    return ", ".join(f"{n}={_short(p[n])}" for n in names if p.get(n) is not None)


class RunResult(Record):
    """One driven-column run (run() or a point of sweep())."""

    PROFILE_FIELDS = ("i", "z_mean", "z_mean_err", "z_std", "z_std_err", "K", "K_err")

    def __repr__(self):
        p = self.get("parameters", {})
        head = _point(p, ("N", "e", "k", "T0", "drive", "plate_A", "plate_omega", "T", "engine", "seed"))
        tail = f"n_coll = {_with_error(self['n_coll'], self.get('n_coll_err'))}"
        tail += ", stationary" if self.get("stationary") else ", NOT stationary"
        if self.get("warnings"):
            tail += f", {len(self['warnings'])} warning{'s' if len(self['warnings']) != 1 else ''}"
        if self.get("reused"):
            tail += ", read back from the store"
        return f"RunResult({head}: {tail})"

    def profile(self):
        """The per-particle profile as a numpy structured array (one row per particle, i = 1 at
        the bottom): i, z_mean, z_mean_err, z_std, z_std_err, K, K_err."""
        out = np.empty(len(self["i"]), dtype=[(f, self[f].dtype) for f in self.PROFILE_FIELDS])
        for f in self.PROFILE_FIELDS:
            out[f] = self[f]
        return out

    def to_pandas(self):
        """The profile as a pandas DataFrame indexed by particle i."""
        return _pandas("RunResult.to_pandas").DataFrame(self.profile()).set_index("i")

    def scalars(self):
        """The parameters and every scalar result of the run as one flat dict (a table row)."""
        row = dict(self["parameters"])
        for key, value in self.items():
            if np.isscalar(value) and key not in ("json",):
                row[key] = value
        return row


class CollapseResult(Record):
    """One collapse count at one (e, k) (collapse())."""

    def __repr__(self):
        p = self.get("parameters", {})
        head = _point(p, ("setup", "N", "e", "k", "engine", "realizations", "seed"))
        tail = f"n_tot = {_with_error(self['n_tot'], self.get('n_tot_err'))}"
        if self.get("collapsed"):
            tail += f", {self['collapsed']} collapsed"
        if not self.get("complete", True):
            tail += ", interrupted"
        return f"CollapseResult({head}: {tail})"

    def launches(self):
        """One row per launch: the per_realization arrays as a numpy structured array."""
        per = self["per_realization"]
        n = len(next(iter(per.values())))
        out = np.empty(n, dtype=[("realization", np.int64)] + [(k, v.dtype) for k, v in per.items()])
        out["realization"] = np.arange(n)
        for k, v in per.items():
            out[k] = v
        return out

    def to_pandas(self):
        """The launches as a pandas DataFrame indexed by realization."""
        return _pandas("CollapseResult.to_pandas").DataFrame(self.launches()).set_index("realization")


class TraceResult(Record):
    """A space-time trace (trace()): t (S), z and v (S x N: heights and velocities), plate (S, a
    vibrating plate's surface, or None), events."""

    def __repr__(self):
        p = self["parameters"]
        t = self["t"]
        span = f"t in [{t[0]:g}, {t[-1]:g}]" if len(t) else "no samples"
        tail = f"{span}, {len(t)} samples, {len(self['events']['t'])} events"
        if self.get("interrupted"):
            tail += ", interrupted"
        return f"TraceResult({_point(p, ('setup', 'N', 'e', 'k', 'drive', 'plate_A', 'plate_omega', 'engine', 'seed'))}: {tail})"

    def to_pandas(self):
        """The heights as a DataFrame: index t, columns z1 .. zN (and z_plate above a plate)."""
        pd = _pandas("TraceResult.to_pandas")
        z = self["z"]
        frame = pd.DataFrame(z, index=pd.Index(self["t"], name="t"), columns=[f"z{i + 1}" for i in range(z.shape[1])])
        if self.get("plate") is not None:
            frame["z_plate"] = self["plate"]
        return frame

    def events_frame(self):
        """The events as a DataFrame (t, kind, i, j, speed)."""
        return _pandas("TraceResult.events_frame").DataFrame(dict(self["events"]))


class SweepResult(list):
    """The points of a sweep() in the order of the command's table (engine, N, T0, drive, A, omega,
    k, T, e, replica), each a RunResult; ``failed`` lists (key, reason) of points that turned unphysical,
    ``db`` the store (or None), ``stored_now`` and ``reused`` how many points were run and stored
    now and read back, ``interrupted`` whether Ctrl-C stopped it; with ``checkpoint_dir``,
    ``resumed`` how many points went on from a saved state and ``saved`` how many were stopped with
    their states saved there."""

    def __init__(self, results, info):
        super().__init__(results)
        self.failed = list(info.get("failed", []))
        self.db = info.get("db")
        self.stored_now = info.get("stored_now", 0)
        self.reused = info.get("reused", 0)
        self.points = info.get("points", len(results))
        self.interrupted = bool(info.get("interrupted", False))
        self.base_seed = info.get("base_seed")
        self.checkpoint_dir = info.get("checkpoint_dir")
        self.resumed = info.get("resumed", 0)
        self.saved = info.get("saved", 0)

    def table(self):
        """One row per point: parameters and scalar results, as a numpy structured array."""
        rows = [r.scalars() for r in self]
        if not rows:
            return np.empty(0)
        names = list(rows[0])
        for row in rows[1:]:
            names += [n for n in row if n not in names]
        columns = {}
        for n in names:
            values = [row.get(n) for row in rows]
            if all(isinstance(v, (bool, np.bool_)) for v in values):
                columns[n] = np.array(values, dtype=bool)
            elif all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) for v in values):
                columns[n] = np.array(values, dtype=np.int64) if all(v < 2**63 for v in values) else np.array(values, dtype=np.uint64)
            elif all(isinstance(v, (int, float, np.number)) and not isinstance(v, bool) for v in values if v is not None):
                columns[n] = np.array([np.nan if v is None else v for v in values], dtype=float)
            else:
                columns[n] = np.array(["" if v is None else str(v) for v in values])
        out = np.empty(len(rows), dtype=[(n, a.dtype) for n, a in columns.items()])
        for n, a in columns.items():
            out[n] = a
        return out

    def to_pandas(self):
        """One row per point as a pandas DataFrame."""
        return _pandas("SweepResult.to_pandas").DataFrame(self.table())

    def __repr__(self):
        axes = []
        for name in ("N", "e", "k", "T0", "drive", "plate_A", "plate_omega", "T", "engine"):
            values = sorted({r["parameters"][name] for r in self}, key=str)
            if len(values) > 1:
                shown = ", ".join(_short(v) for v in values[:4]) + (", ..." if len(values) > 4 else "")
                axes.append(f"{name} in {{{shown}}}")
        text = f"SweepResult({len(self)} of {self.points} points"
        if axes:
            text += "; " + "; ".join(axes)
        text += f"; {self.stored_now} run and stored now, {self.reused} read back" if self.db else ""
        if self.failed:
            text += f"; {len(self.failed)} failed"
        if self.interrupted:
            text += "; interrupted"
        return text + ")"

    def _repr_pretty_(self, printer, cycle):
        printer.text(repr(self))


def warn_quality(results, stacklevel=3):
    """Each run's verdicts as QualityWarning: one warning per verdict of a single run, one per
    kind of verdict (with the number of points) for a sweep."""
    if isinstance(results, RunResult):
        for w in results.get("warnings", []):
            warnings.warn(w, QualityWarning, stacklevel=stacklevel)
        return
    kinds = {}
    for r in results:
        for w in r.get("warnings", []):
            # The verdict without its numbers: "12 of 75 profile error bars found no ..." and the
            # halves after ";" differ from point to point, the verdict does not.
            kind = re.sub(r"^\d+ of \d+ ", "", w).split(";")[0].split(" (")[0]
            kinds.setdefault(kind, []).append(r)
    for kind, rs in kinds.items():
        warnings.warn(f"{len(rs)} of {len(results)} points: {kind} (each point's .warnings says more)", QualityWarning,
                      stacklevel=stacklevel)
