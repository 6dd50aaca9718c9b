"""granchain from Python: driven columns, sweeps, collapse counts, traces, the paper's closed
forms, results stores.

run(), sweep(), collapse() and trace() are the simulations of ``granchain run``, ``sweep``,
``collapse`` and ``trace`` (the same code, the same numbers for the same seed); their keyword
arguments are the CLI's flags (dt_factor for --dt-factor), validated by the CLI's own code, so bad
input raises ValueError with the CLI's message naming the keyword. They return results with a
short repr, attribute access and numpy/pandas conversions (granchain.results); a result's quality
verdicts are raised as granchain.QualityWarning; Ctrl-C stops sweep, collapse and trace within a
fraction of a second and raises granchain.Interrupted holding what finished. The theory functions
are the closed forms of src/theory; Store, export() and analyze() read a results store;
compare_forms() and local_exponents() analyse a count against k. See docs/python.md.
"""

import inspect as _inspect
import sys as _sys
import warnings as _warnings

from . import _granchain

# Every result's provenance records the program that made it (the command line of a script).
_granchain._set_invocation(" ".join(["/usr/bin/python3"] + [str(a) for a in _sys.argv]) + " (granchain Python module)")
from ._granchain import (  # noqa: F401  (the public API)
    StoreError,
    UnphysicalStateError,
    __version__,
    collisions_slope_per_ln_k,
    compare_forms,
    cushion_Nc_wall,
    ec3,
    ec_free,
    ec_wall_cushion,
    ec_wall_cushion_asymptotic,
    ec_wall_icw,
    ec_wall_icw_asymptotic,
    elastic_column,
    f_shift,
    k_slope,
    local_exponents,
    m_prime_star,
    m_star,
    ntot_slope_per_ln_k,
    parse_value_list,
    q_ratio,
    collapse_parameters,
    run_parameters,
)
from .results import (  # noqa: F401
    CollapseResult,
    Interrupted,
    QualityWarning,
    Record,
    RunResult,
    SweepResult,
    TraceResult,
)
from .results import warn_quality as _warn_quality
from .store import Store, analyze, export  # noqa: F401


def _signature(table, extra):
    """Keyword-only parameters: one per entry of a parameter table (None: the command's default),
    then the function's own."""
    keywords = [_inspect.Parameter(p["name"].replace("-", "_"), _inspect.Parameter.KEYWORD_ONLY, default=None)
                for p in table]
    keywords += [_inspect.Parameter(name, _inspect.Parameter.KEYWORD_ONLY, default=value) for name, value in extra]
    return _inspect.Signature(keywords)


def _table_doc(title, table):
    return f"\n    Parameters ({title}):\n" + "".join(
        f"\n        {p['name'].replace('-', '_')}: {p['help']}" for p in table)


def run(**kwargs):
    """Simulate the driven column once, as ``granchain run`` (None: the CLI's default).

    Returns a RunResult (a dict whose keys are also attributes; .profile() and .to_pandas() give
    the profile as a table): parameters, n_coll, n_coll_err, n_coll_blocks, n_coll_converged,
    floor_rate(_err), pp_rate(_err), particle_collisions, floor_hits, stationary (bool),
    stationarity (the halves compared), blocking (the blocking curves of n_coll and of the mean
    height: blocks, error, lag1 per level), warnings (the verdicts, each also raised as
    granchain.QualityWarning), per-particle numpy arrays i, z_mean, z_mean_err, z_std,
    z_std_err, K, K_err (i = 1 at the bottom), derived (D, tau_c, dt, sample_interval, samples),
    cost (steps, events, wall_seconds, cpu_seconds), code_version, stored (None, or db and run_id
    with db=PATH), and json (the text of
    ``granchain run --json``).

    db=PATH stores the run in that results store (created if missing), as the CLI does without
    --no-db; audit=True is --audit; progress=callable(dict) is called about every 0.5 s with t,
    t_total, in_transient, steps, events and wall_seconds. Ctrl-C stops a run (KeyboardInterrupt).
    checkpoint=PATH (``run --checkpoint``): the run keeps its state in PATH, saved every
    checkpoint_every seconds (600) and on Ctrl-C (the KeyboardInterrupt then says where); the same
    call resumes it to the uninterrupted result bit for bit (resumed_at: the time it went on from)
    and removes PATH once the result is returned (and stored).
    Raises ValueError (bad input, the CLI's message), UnphysicalStateError, StoreError, OSError (a
    checkpoint that cannot be written).
    """
    run.__signature__.bind(**kwargs)  # TypeError for a keyword that is no parameter
    result = RunResult(_granchain.run(**kwargs))
    _warn_quality(result)
    return result


run.__signature__ = _signature([p for p in run_parameters() if p["name"] != "db"],
                               [("db", None), ("audit", False), ("progress", None)])
run.__doc__ += _table_doc("the flags of ``granchain run``; None or left out: the command's default",
                          [p for p in run_parameters() if p["name"] != "db"])  # db: not stored unless given


def collapse(**kwargs):
    """Count the collisions n_tot of an inelastic collapse at one (e, k), as ``granchain collapse``.

    N >= 2 spheres launched inward in free space (setup='free', Sec. III.D) or thrown against a
    wall (setup='wall'); k is required for the soft engines and left out for engine='hard';
    stop: 'ends' (the paper's, free space) or 'strict'; realizations launches, launch r from
    derive_seed(seed, r) (the same launches at every e and k); threads: default all cores (the
    numbers do not depend on it); collapse_collisions (default 1000) and collapse_time (default
    1e-9) set the hard engine's collapse watch and are refused for the soft engines. db=PATH stores
    the count and, without record_collisions, carries it over sittings: each launch is kept in the
    store as it finishes, and the same call after an interruption counts only the launches missing
    (the same numbers, bit for bit); record_collisions=True adds every collision (and runs every
    launch).

    progress: None (a line rewritten in place on a terminal or in a notebook, nothing otherwise),
    False, True, or callable(dict) with done, total, collisions, elapsed. Ctrl-C ends the count
    within a fraction of a second and raises granchain.Interrupted whose .result is the count over
    the launches finished before the first unfinished one (the same numbers as a count of that many
    launches; not stored, complete=False; with db, every launch finished is kept for the next call).

    Returns a CollapseResult (a dict whose keys are also attributes; .launches() and .to_pandas()
    give one row per launch): parameters, D, tau_c, n_tot and n_tot_err (mean and standard error over the
    launches that did not collapse; nan if none finished), n_tot_min, n_tot_max, collapsed (how
    many launches collapsed, hard spheres), collisions, grazing_contacts, held_contacts,
    wall_seconds, per_realization (numpy arrays n_tot, particle_collisions, wall_hits, collapsed,
    t_stop, grazing_contacts, held_contacts), collisions_log (with record_collisions: arrays
    realization, collision, t_begin, t_end, i, j, speed_in, speed_out), stored, json.
    Raises ValueError (bad input, the CLI's message), UnphysicalStateError, StoreError.
    """
    collapse.__signature__.bind(**kwargs)  # TypeError for a keyword that is no parameter
    kwargs["progress"] = _progress_callback(kwargs.get("progress"), "collapse", "launches")
    result = CollapseResult(_granchain.collapse(**kwargs))
    if result.pop("interrupted"):
        raise Interrupted(result, f"{result.parameters.realizations} launches finished"
                          + ("" if result.complete else " (not stored)"))
    return result


collapse.__signature__ = _signature(collapse_parameters(), [("db", None), ("record_collisions", False), ("progress", None)])
collapse.__doc__ += _table_doc("the flags of ``granchain collapse``, one e and one k per call; None or left out: "
                               "the command's default", collapse_parameters())


def _in_notebook_or_terminal():
    return "ipykernel" in _sys.modules or (hasattr(_sys.stderr, "isatty") and _sys.stderr.isatty())


class _ProgressLine:
    """One line on standard error rewritten in place (a carriage return), which a terminal and a
    Jupyter notebook both show as a single updating line; a newline when the work ends."""

    def __init__(self, label, unit):
        self.label, self.unit, self.width, self.closed = label, unit, 0, False

    def __call__(self, p):
        if self.closed:
            return
        text = f"{self.label}: {p['done']}/{p['total']} {self.unit}, {_duration(p['elapsed'])}"
        if p.get("eta") is not None and p["eta"] == p["eta"] and p["done"] < p["total"]:
            text += f", ETA {_duration(p['eta'])}"
        if p.get("failed"):
            text += f", {p['failed']} failed"
        self.width = max(self.width, len(text))
        _sys.stderr.write("\r" + text.ljust(self.width))
        if p["done"] >= p["total"] or p.get("final"):
            _sys.stderr.write("\n")
            self.closed = True
        _sys.stderr.flush()


def _duration(seconds):
    if seconds < 60:
        return f"{seconds:.1f} s"
    if seconds < 3600:
        return f"{seconds / 60:.1f} min"
    return f"{seconds / 3600:.2f} h"


def _progress_callback(progress, label, unit):
    """The progress argument as the callable the compiled part calls (or None)."""
    if progress is None:
        progress = _in_notebook_or_terminal()
    if progress is True:
        return _ProgressLine(label, unit)
    if progress is False:
        return None
    return progress


def sweep(**kwargs):
    """Run a grid of driven-column runs, as ``granchain sweep`` (None: the command's default).

    Grid parameters (N, e, k, T0, T, engine) take a list, a tuple, a numpy array or the CLI's
    text ("0.80:0.90:0.002", "1e5:1e10:x10"); the others one value. replicas: independent runs per
    point; seed: the base seed, from which each point's seed derives with its parameters and
    replica (the command's seeds: the same numbers as ``granchain sweep`` with the same flags);
    threads: points at once (default all cores); db=PATH: each finished point is stored at once and
    points the store holds are read back, not run (call again to resume); progress: None (a line
    rewritten in place on a terminal or in a notebook, nothing otherwise), False, True, or
    callable(dict) with done, failed, total, reused, elapsed, eta, collisions_per_second.

    Returns a SweepResult: a list of RunResult in the order of the command's table (engine, N, T0,
    k, T, e, replica), with .table() (numpy), .to_pandas(), .failed ((key, reason) of points that
    turned unphysical, also warned), .stored_now, .reused, .db. Each kind of quality verdict is
    raised once as granchain.QualityWarning with the number of points. Ctrl-C stops the sweep
    within about a second: running points are abandoned (neither stored nor returned) and
    granchain.Interrupted is raised, its .result the SweepResult of the points that finished.
    checkpoint_dir=DIR (``sweep --checkpoint-dir``): each running point keeps its state in DIR,
    saved every checkpoint_every seconds (600) and on Ctrl-C, and the next call resumes it to the
    uninterrupted result bit for bit (.resumed, .saved count them; each point's resumed_at is the
    time it went on from, None for a fresh start).
    Raises ValueError for bad input (the CLI's message), StoreError, OSError (a state that cannot
    be written).
    """
    sweep.__signature__.bind(**kwargs)
    kwargs["progress"] = _progress_callback(kwargs.get("progress"), "sweep", "points")
    out = _granchain.sweep(**kwargs)
    result = SweepResult([RunResult(r) for r in out["results"]], out)
    for key, reason in result.failed:
        _warnings.warn(f"point {key} turned unphysical and was not stored: {reason}", QualityWarning, stacklevel=2)
    if result.interrupted:
        raise Interrupted(result, f"{len(result)} of {result.points} points finished"
                          + (f", those run now stored in {result.db}" if result.db else "")
                          + (f"; the states of {result.saved} running points are saved in {result.checkpoint_dir}"
                             " (call again to resume them)" if result.saved else ""))
    _warn_quality(result)
    return result


_sweep_table = [p for p in run_parameters() if p["name"] not in ("db", "audit", "checkpoint")]
sweep.__signature__ = _signature(_sweep_table, [("db", None), ("replicas", None), ("threads", None), ("progress", None),
                                                ("checkpoint_dir", None)])
sweep.__doc__ += _table_doc("the flags of ``granchain sweep``; lists for the grid parameters", _sweep_table)


def trace(**kwargs):
    """Record the heights z_i(t) of every particle on a grid of times, as ``granchain trace``.

    setup='driven' (default): the trajectory of run() with the same parameters and seed;
    setup='free': launch `realization` of collapse() (a, v0, dv0 as there). t_from, t_to (the
    command's --from and --to; `from` is a Python keyword), dt: the window and sampling interval.

    Returns a TraceResult: t (S samples), z (S x N, particle 1 at the bottom), events (t, kind,
    i, j, speed; the floor as particle 0), parameters; .to_pandas() and .events_frame(). Ctrl-C
    stops it and raises granchain.Interrupted, its .result the samples recorded so far.
    """
    trace.__signature__.bind(**kwargs)
    result = TraceResult(_granchain.trace(**kwargs))
    if result.pop("interrupted"):
        raise Interrupted(result, f"{len(result.t)} samples recorded")
    return result


def _trace_keywords():
    names = []
    for p in _granchain.trace_parameters():
        name = {"from": "t_from", "to": "t_to"}.get(p["name"], p["name"])
        names.append(dict(p, name=name))
    return names


trace.__signature__ = _signature(_trace_keywords(), [])
trace.__doc__ += _table_doc("the flags of ``granchain trace``; None or left out: the command's default", _trace_keywords())
