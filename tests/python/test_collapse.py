"""granchain.collapse: the CLI's counts, per-launch arrays, the three-body growth with k."""

import csv
import io

import numpy as np
import pytest

import granchain
from conftest import cli_error, ctrl_c_after, keyword_form


def test_count_is_the_clis(cli, cli_json, tmp_path):
    r = granchain.collapse(N=3, e=0.05, k=1e6, realizations=40, seed=3, record_collisions=True)
    events = tmp_path / "events.csv"
    j = cli_json("collapse", "--N", 3, "--e", 0.05, "--k", "1e6", "--realizations", 40, "--seed", 3,
                 "--events", events, "--no-db", "-q")
    obs = j["points"][0]["observables"]
    assert r["n_tot"] == obs["n_tot"] and r["n_tot_err"] == obs["n_tot_err"]
    assert (r["n_tot_min"], r["n_tot_max"], r["collapsed"]) == (obs["n_tot_min"], obs["n_tot_max"], obs["collapsed"])
    per = r["per_realization"]
    assert per["n_tot"].shape == (40,) and per["n_tot"].dtype == np.int64
    assert per["n_tot"].mean() == pytest.approx(r["n_tot"], rel=1e-15)
    assert int(per["particle_collisions"].sum()) == obs["particle_collisions"]
    assert np.all(per["t_stop"] > 0) and not per["collapsed"].any()
    # Every collision, as `--events` writes it (17 significant digits: exact).
    rows = list(csv.DictReader(io.StringIO(events.read_text())))
    log = r["collisions_log"]
    assert len(rows) == len(log["t_begin"]) == per["n_tot"].sum()
    assert [float(x["t_begin"]) for x in rows] == log["t_begin"].tolist()
    assert [int(x["realization"]) for x in rows] == log["realization"].tolist()
    assert [float(x["speed_out"]) for x in rows] == log["speed_out"].tolist()


def test_three_body_counts_grow_with_k_below_ec3():
    # Below e_c(3) = 7 - 4 sqrt 3 three spheres collapse as hard spheres; soft ones count more
    # collisions the stiffer they are, about -ln10/ln q per decade of k (docs/collapse.md).
    e = 0.05
    assert e < granchain.ec_free(3)
    counts = [granchain.collapse(N=3, e=e, k=k, realizations=100, seed=1) for k in (1e4, 1e6, 1e8)]
    means = [c["n_tot"] for c in counts]
    assert means[0] < means[1] < means[2]
    s = granchain.k_slope(counts[1], counts[2])
    assert s["launches"] == 100 and s["slope_per_log10_k"] > 10 * s["error"]
    assert s["theory_all_collisions"] == pytest.approx(-np.log(10) / np.log(granchain.q_ratio(e)))
    assert 0.5 * s["theory_all_collisions"] < s["slope_per_log10_k"] < 1.1 * s["theory_all_collisions"]
    # Per launch, no count falls when k grows (the same launches at every k).
    assert np.all(counts[2]["per_realization"]["n_tot"] >= counts[0]["per_realization"]["n_tot"])


def test_three_body_count_converges_above_ec3():
    a, b = (granchain.collapse(N=3, e=0.5, k=k, realizations=50) for k in (1e6, 1e8))
    assert np.all(b["per_realization"]["n_tot"] == 2)
    assert abs(granchain.k_slope(a, b)["slope_per_log10_k"]) < 0.05


def test_hard_spheres_collapse_only_below_ec3():
    below = granchain.collapse(N=3, e=0.05, engine="hard", realizations=40)
    above = granchain.collapse(N=3, e=0.1, engine="hard", realizations=40)
    assert below["parameters"]["k"] == above["parameters"]["k"] == np.inf
    assert below["collapsed"] == below["per_realization"]["collapsed"].sum() > 0
    assert above["collapsed"] == 0 and not above["per_realization"]["collapsed"].any()
    # n_tot averages the launches that did not collapse.
    done = ~below["per_realization"]["collapsed"]
    assert below["n_tot"] == pytest.approx(below["per_realization"]["n_tot"][done].mean(), rel=1e-15)


@pytest.mark.parametrize("kwargs,flags", [
    (dict(N=1, k=1e6), ["--N=1", "--k=1e6"]),
    (dict(e=0, k=1e6), ["--e=0", "--k=1e6"]),
    (dict(engine="hard", k=1e6), ["--engine=hard", "--k=1e6"]),
    (dict(k=1e6, tc=1e-6), ["--k=1e6", "--tc=1e-6"]),
    (dict(k=1e6, setup="wall", stop="ends"), ["--k=1e6", "--setup=wall", "--stop=ends"]),
    (dict(k=1e6, realizations=0), ["--k=1e6", "--realizations=0"]),
    (dict(k=1e6, dt_factor=1), ["--k=1e6", "--dt-factor=1"]),
])
def test_bad_input_raises_value_error_with_the_clis_message(cli, kwargs, flags):
    with pytest.raises(ValueError) as info:
        granchain.collapse(**kwargs)
    names = [q["name"] for q in granchain.collapse_parameters()]
    assert str(info.value) == keyword_form(cli_error(cli("collapse", *flags, "--no-db")), names)
    assert "--" not in str(info.value)


def test_soft_engines_need_one_k():
    with pytest.raises(ValueError, match="^k: give the elastic constant"):
        granchain.collapse(N=3, e=0.05)


def test_keywords_are_the_parameter_tables():
    import inspect
    run_names = {p["name"].replace("-", "_") for p in granchain.run_parameters()}
    assert run_names == set(inspect.signature(granchain.run).parameters) - {"audit", "progress"}
    collapse_names = {p["name"].replace("-", "_") for p in granchain.collapse_parameters()}
    assert collapse_names == set(inspect.signature(granchain.collapse).parameters) - {"db", "record_collisions", "progress"}
    assert all(p["range"] and p["range"] in p["help"] for p in granchain.collapse_parameters())


def test_numbers_typed_or_as_text_count_the_same():
    a = granchain.collapse(N=3, e=0.05, k=1e6, realizations=20, seed=2)
    b = granchain.collapse(N="3", e="0.05", k="1e6", realizations="20", seed="2")
    c = granchain.collapse(N=np.int64(3), e=np.float64(0.05), k=np.float64(1e6), realizations=20, seed=2)
    assert a["n_tot"] == b["n_tot"] == c["n_tot"]
    assert np.array_equal(a["per_realization"]["n_tot"], c["per_realization"]["n_tot"])


def test_ctrl_c_ends_a_count_within_a_second_keeping_the_launches_done(tmp_path):
    # SIGINT while launches of seconds each run: Interrupted within a second, holding the count over
    # the launches finished before the first unfinished one, which is exactly a count of that many
    # launches (the same launches: launch r from derive_seed(seed, r)); nothing is stored.
    db = tmp_path / "c.db"
    kwargs = dict(N=25, e=0.3, k=1e9, seed=3, threads=2)
    with ctrl_c_after(1.5) as c:
        with pytest.raises(granchain.Interrupted) as info:
            granchain.collapse(realizations=100000, db=db, progress=False, **kwargs)
    assert c.elapsed < 1.0
    part = info.value.result
    assert isinstance(part, granchain.CollapseResult) and not part.complete
    n = part.parameters.realizations
    assert 2 <= n < 100000 and len(part.per_realization.n_tot) == n
    whole = granchain.collapse(realizations=n, progress=False, **kwargs)
    assert part.per_realization.n_tot.tolist() == whole.per_realization.n_tot.tolist()
    assert part.n_tot == whole.n_tot and part.n_tot_err == whole.n_tot_err
    assert not db.exists() or len(granchain.Store(db).collapse()) == 0


def test_an_interrupted_count_with_a_store_continues_where_it_stopped(tmp_path):
    # With db, every launch finished is kept in the store: the same call after Ctrl-C counts only the
    # launches missing and gives the numbers of a count run in one go, bit for bit.
    import sqlite3
    db = tmp_path / "c.db"
    kwargs = dict(N=50, e=0.3, k=1e9, seed=5, threads=2, realizations=60, progress=False)
    with ctrl_c_after(1.0):
        with pytest.raises(granchain.Interrupted):
            granchain.collapse(db=db, **kwargs)
    kept = sqlite3.connect(db).execute("SELECT count(*) FROM collapse_launches").fetchone()[0]
    assert 1 <= kept < 60, "the count finished before Ctrl-C or kept nothing: the test shows nothing"
    done = []
    resumed = granchain.collapse(db=db, **dict(kwargs, progress=lambda d: done.append(d["done"])))
    assert resumed.complete and resumed.stored["collapse_run_id"] > 0
    whole = granchain.collapse(**kwargs)
    assert resumed.per_realization.n_tot.tolist() == whole.per_realization.n_tot.tolist()
    assert resumed.per_realization.t_stop.tolist() == whole.per_realization.t_stop.tolist()
    assert resumed.n_tot == whole.n_tot and resumed.n_tot_err == whole.n_tot_err
    assert sqlite3.connect(db).execute("SELECT count(*) FROM collapse_launches").fetchone()[0] == 0


def test_a_count_is_a_record_with_a_short_repr():
    r = granchain.collapse(N=3, e=0.05, k=1e6, realizations=20, progress=False)
    assert isinstance(r, dict) and r.n_tot == r["n_tot"] and r.parameters.N == 3
    assert len(repr(r)) < 200 and "n_tot = " in repr(r)
    launches = r.launches()
    assert launches["realization"].tolist() == list(range(20)) and launches["n_tot"].tolist() == r.per_realization.n_tot.tolist()
    pd = pytest.importorskip("pandas")
    frame = r.to_pandas()
    assert isinstance(frame, pd.DataFrame) and frame["n_tot"].mean() == pytest.approx(r.n_tot, rel=1e-12)
