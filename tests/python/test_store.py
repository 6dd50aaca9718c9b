"""granchain.Store / export: the rows `granchain export` gives, typed, with the same filters."""

import csv
import json
import io
import math

import numpy as np
import pytest

import granchain
from conftest import cli_error


@pytest.fixture(scope="module")
def store(tmp_path_factory, cli):
    """A store made by the CLI: three soft runs, a hard-sphere run and a collapse count."""
    db = tmp_path_factory.mktemp("store") / "s.db"
    for e in (0.9, 0.8, 0.7):
        assert cli("run", "--N", 3, "--e", e, "--k", "1e5", "--T", 20, "--db", db, "-q").returncode == 0
    assert cli("run", "--N", 2, "--engine", "hard", "--T", 20, "--db", db, "-q").returncode == 0
    assert cli("collapse", "--N", 3, "--e", 0.05, "--k", "1e4", "--realizations", 5, "--db", db, "-q").returncode == 0
    return db


def cli_rows(cli, *args):
    p = cli("export", *args)
    assert p.returncode == 0, p.stderr
    return list(csv.DictReader(io.StringIO(p.stdout)))


def same_value(a, text):
    """A value of the module against the CLI's CSV field."""
    if text == "":
        return a is None or a == "" or (isinstance(a, float) and math.isnan(a))
    if isinstance(a, (float, np.floating)):
        return float(a) == float(text)  # exact, inf included
    return str(a) == text


@pytest.mark.parametrize("table", ["runs", "profiles", "collapse", "realizations"])
def test_rows_are_the_clis(cli, store, table):
    rows = granchain.export(store, table)
    expected = cli_rows(cli, "--db", store, "--table", table)
    assert len(rows) == len(expected) > 0
    assert list(rows.dtype.names) == list(expected[0].keys())
    for got, want in zip(rows, expected):
        for name in rows.dtype.names:
            assert same_value(got[name].item(), want[name]), (table, name, got[name], want[name])


def test_columns_are_typed(store):
    runs = granchain.Store(store).runs()
    assert runs["N"].dtype == np.int64 and runs["seed"].dtype == np.int64
    assert runs["T0"].dtype == np.float64 and runs["T"].dtype == np.float64  # reals even when whole
    assert runs["engine"].tolist() == ["exact"] * 3 + ["hard"]
    assert runs["k"].tolist() == [1e5, 1e5, 1e5, math.inf]  # hard spheres: k = inf, not NULL
    assert np.isnan(runs["replica"]).all()  # NULL for runs of `granchain run`
    d = granchain.export(store, "runs", as_dict=True)  # the CLI's columns, the store's order
    renamed = {"damping_D": "D"}
    assert {renamed.get(n, n) for n in d} == set(runs.dtype.names)
    assert sorted(d["n_coll"].tolist()) == sorted(runs["n_coll"].tolist())


def test_store_tables_read_as_a_notebook_reads_them(store):
    s = granchain.Store(store)
    runs = s.runs()
    # sorted by the parameters (engine, N, T0, k, T, e, seed), not by when they were stored
    keys = list(zip(runs["engine"], runs["N"], runs["T0"], runs["k"], runs["T"], runs["e"], runs["seed"]))
    assert keys == sorted(keys)
    assert runs["stationary"].dtype == bool and runs["n_coll_converged"].dtype == bool
    assert runs["created_utc"].dtype == np.dtype("datetime64[s]")
    assert (runs["created_utc"] <= np.datetime64("now")).all() and (runs["created_utc"] > np.datetime64("2026-01-01")).all()
    # the names of run()'s results: K (the store's K_mean, beside k in SQL), D (damping_D)
    prof = s.profiles(N=3)
    assert "K" in prof.dtype.names and "K_mean" not in prof.dtype.names and "D" in runs.dtype.names
    assert set(granchain.RunResult.PROFILE_FIELDS) <= set(prof.dtype.names)
    with pytest.warns(granchain.QualityWarning):
        r = granchain.run(N=3, e=0.8, k=1e5, T=1)
    assert r.derived.D == runs["D"][runs["e"] == 0.8][0]


@pytest.mark.parametrize("kwargs,flags", [
    (dict(e=0.9), ["--e", "0.9"]),
    (dict(e=[0.7, 0.9]), ["--e", "0.7,0.9"]),
    (dict(e="0.7:0.8:0.1"), ["--e", "0.7:0.8:0.1"]),
    (dict(engine="hard"), ["--engine", "hard"]),
    (dict(N=3, where="e < 0.85"), ["--N", "3", "--where", "e < 0.85"]),
    (dict(k=1e5, T0=1, T=20), ["--k", "1e5", "--T0", "1", "--T", "20"]),
])
def test_filters_select_what_the_cli_selects(cli, store, kwargs, flags):
    ids = granchain.export(store, "runs", **kwargs)["id"].tolist()
    assert ids == [int(r["id"]) for r in cli_rows(cli, "--db", store, *flags)]
    assert ids  # every filter here selects something


def test_profiles_hold_every_particle(store):
    prof = granchain.Store(store).profiles(N=3)
    assert len(prof) == 9 and prof["i"].tolist() == [1, 2, 3] * 3
    assert np.all(np.diff(prof["z_mean"].reshape(3, 3), axis=1) > 0)  # the column is ordered


def test_bad_selections_raise_value_error_with_the_clis_message(cli, store, tmp_path):
    with pytest.raises(ValueError) as info:
        granchain.export(store, "collapse", T0=1)
    assert str(info.value) == cli_error(cli("export", "--db", store, "--table", "collapse", "--T0", "1"))
    with pytest.raises(ValueError) as info:
        granchain.export(store, where="no_such_column > 1")
    assert str(info.value) == cli_error(cli("export", "--db", store, "--where", "no_such_column > 1"))
    missing = tmp_path / "missing.db"
    with pytest.raises(ValueError) as info:
        granchain.Store(missing)
    assert str(info.value) == cli_error(cli("export", "--db", missing))
    assert not missing.exists()  # read-only: nothing created


def test_analyze_gives_what_the_cli_analyze_json_gives(cli, tmp_path):
    """granchain.analyze is `granchain analyze --json`: N = 3 at e = 0.3 and 0.9 over k = 1e4..1e6."""
    db = tmp_path / "a.db"
    p = cli("sweep", "--N", 3, "--e", "0.3,0.9", "--k", "1e4:1e6:x10", "--T", 100, "--db", db, "-q")
    assert p.returncode == 0, p.stderr
    ours = granchain.analyze(db, N=3, k_min=1e4)
    p = cli("analyze", "--db", db, "--N", 3, "--k-min", "1e4", "--json")
    assert p.returncode == 0, p.stderr
    theirs = json.loads(p.stdout)
    theirs.pop("provenance")
    assert ours == theirs
    (family,) = ours["families"]
    assert family["N"] == 3 and [c["e"] for c in family["curves"]] == [0.3, 0.9]
    assert all(len(c["n_coll_of_k"]) == 3 and c["classified"] for c in family["curves"])
    assert granchain.Store(db).analyze(N=3, k_min=1e4) == ours
    assert granchain.analyze(db, N=4)["families"] == []
    # The filters of the CLI: one e, a window of k, a window length.
    window = granchain.analyze(db, e=0.3, k="1e5:1e6:x10", T=100)
    p = cli("analyze", "--db", db, "--e", "0.3", "--k", "1e5:1e6:x10", "--T", 100, "--json")
    theirs = json.loads(p.stdout)
    theirs.pop("provenance")
    assert window == theirs
    (curve,) = window["families"][0]["curves"]
    assert len(curve["n_coll_of_k"]) == 2 and not curve["classified"]
    with pytest.raises(ValueError) as info:
        granchain.analyze(db, k_min=-1)
    assert str(info.value) == cli_error(cli("analyze", "--db", db, "--k-min", "-1"))
