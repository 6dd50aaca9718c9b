"""granchain from Python: driven columns, collapse counts, the paper's closed forms, results stores.

    PYTHONPATH=build/python /usr/bin/python3 -c "import granchain"

run() and collapse() are the simulations of ``granchain run`` and ``granchain collapse`` (the
same code, the same numbers for the same seed); their keyword arguments are the CLI's flags
(dt_factor for --dt-factor), validated by the CLI's own code, so bad input raises ValueError with
the message the CLI prints. Both release the GIL: threads run several at once. The theory
functions are the closed forms of src/theory; Store, export() and analyze() read a results store;
compare_forms() and local_exponents() analyse a count against k. See docs/python.md.
"""

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


def run(*, N=None, e=None, k=None, T0=None, T=None, transient=None, seed=None, engine=None,
        dt_factor=None, tc=None, m=None, d=None, g=None, sample_interval=None, bins=None,
        db=None, audit=False, progress=None):
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

    Parameters (the flags of ``granchain run``):
    """
    args = dict(N=N, e=e, k=k, T0=T0, T=T, transient=transient, seed=seed, engine=engine,
                dt_factor=dt_factor, tc=tc, m=m, d=d, g=g, sample_interval=sample_interval,
                bins=bins, db=db, audit=audit, progress=progress)
    return _granchain.run(**args)


run.__doc__ += "".join(f"\n        {p['name'].replace('-', '_')}: {p['help']}"
                       for p in run_parameters() if p["name"] != "db")  # db: not stored unless given


def collapse(*, N=3, e=0.03, k=None, engine="exact", setup="free", a=1.0, v0=1.0, dv0=0.1,
             stop=None, realizations=1000, seed=1, threads=None, dt_factor=100.0, tc=None,
             collapse_collisions=None, collapse_time=None, db=None, record_collisions=False):
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
    args = dict(N=N, e=e, k=k, engine=engine, setup=setup, a=a, v0=v0, dv0=dv0, stop=stop,
                realizations=realizations, seed=seed, threads=threads, dt_factor=dt_factor, tc=tc,
                collapse_collisions=collapse_collisions, collapse_time=collapse_time, db=db,
                record_collisions=record_collisions)
    return _granchain.collapse(**args)


collapse.__doc__ += "\n    Parameters (the flags of ``granchain collapse``, one e and one k per call):\n" + "".join(
    f"\n        {p['name'].replace('-', '_')}: {p['help']}" for p in collapse_parameters())
