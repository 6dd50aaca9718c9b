"""granchain from Python: driven columns, collapse counts, the paper's closed forms, results stores.

    PYTHONPATH=build/python /usr/bin/python3 -c "import granchain"

run() and collapse() are the simulations of ``granchain run`` and ``granchain collapse`` (the
same code, the same numbers for the same seed); their keyword arguments are the CLI's flags
(dt_factor for --dt-factor), validated by the CLI's own code, so bad input raises ValueError with
the message the CLI prints. Both release the GIL: threads run several at once. The theory
functions are the closed forms of src/theory; Store, export() and analyze() read a results store;
compare_forms() and local_exponents() analyse a count against k. See docs/python.md.
"""

import inspect as _inspect
import sys as _sys

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

    Returns a dict: parameters (dict), n_coll, n_coll_err, n_coll_blocks, n_coll_converged,
    floor_rate(_err), pp_rate(_err), particle_collisions, floor_hits, stationary (bool) and
    stationarity (the halves compared), per-particle numpy arrays i, z_mean, z_mean_err, z_std,
    z_std_err, K, K_err (i = 1 at the bottom), derived (D, tau_c, dt, sample_interval, samples),
    cost (steps, events, wall_seconds, cpu_seconds), code_version, stored (None, or db and run_id
    with db=PATH), and json (the text of
    ``granchain run --json``).

    db=PATH stores the run in that results store (created if missing), as the CLI does without
    --no-db; audit=True is --audit; progress=callable(dict) is called about every 0.5 s with t,
    t_total, in_transient, steps, events and wall_seconds. Ctrl-C stops a run (KeyboardInterrupt).
    Raises ValueError (bad input, the CLI's message), UnphysicalStateError, StoreError.
    """
    run.__signature__.bind(**kwargs)  # TypeError for a keyword that is no parameter
    return _granchain.run(**kwargs)


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
    the count; record_collisions=True adds every collision.

    Returns a dict: parameters, D, tau_c, n_tot and n_tot_err (mean and standard error over the
    launches that did not collapse; nan if none finished), n_tot_min, n_tot_max, collapsed (how
    many launches collapsed, hard spheres), collisions, grazing_contacts, held_contacts,
    wall_seconds, per_realization (numpy arrays n_tot, particle_collisions, wall_hits, collapsed,
    t_stop, grazing_contacts, held_contacts), collisions_log (with record_collisions: arrays
    realization, collision, t_begin, t_end, i, j, speed_in, speed_out), stored, json.
    Raises ValueError (bad input, the CLI's message), UnphysicalStateError, StoreError.
    """
    collapse.__signature__.bind(**kwargs)  # TypeError for a keyword that is no parameter
    return _granchain.collapse(**kwargs)


collapse.__signature__ = _signature(collapse_parameters(), [("db", None), ("record_collisions", False)])
collapse.__doc__ += _table_doc("the flags of ``granchain collapse``, one e and one k per call; None or left out: "
                               "the command's default", collapse_parameters())
