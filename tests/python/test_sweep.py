"""granchain.sweep: the points, seeds and numbers of `granchain sweep`, resumable in a store,
interruptible by Ctrl-C within a second, with quality verdicts as warnings."""

import warnings

import numpy as np
import pytest

import granchain
from conftest import cli_error, ctrl_c_after, keyword_form


def quiet_sweep(**kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", granchain.QualityWarning)
        return granchain.sweep(progress=False, **kwargs)


def test_a_sweep_is_the_clis_point_for_point(cli, tmp_path):
    # The same grid through the command and the module: the same keys, seeds and numbers, bit for bit.
    db = tmp_path / "cli.db"
    p = cli("sweep", "--N", "3,4", "--e", "0.5:0.7:0.2", "--k", "1e5", "--T", 10, "--replicas", 2, "--seed", 7,
            "--threads", 2, "--db", db, "-q")
    assert p.returncode == 0, p.stderr
    stored = {r["point_key"]: r for r in granchain.Store(db).runs()}
    s = quiet_sweep(N=[3, 4], e=np.array([0.5, 0.7]), k=1e5, T=10, replicas=2, seed=7, threads=2)
    assert len(s) == s.points == 8 and not s.failed and s.db is None
    for r in s:
        row = stored[r.key]
        assert r.parameters.seed == row["seed"] and r.n_coll == row["n_coll"] and r.n_coll_err == row["n_coll_err"]
    # the command's table order: N, then e, then replica
    assert [(r.parameters.N, r.parameters.e, r.replica) for r in s] == sorted((r.parameters.N, r.parameters.e, r.replica) for r in s)
    table = s.table()
    assert table["n_coll"].tolist() == [r.n_coll for r in s] and table["N"].dtype == np.int64


def test_a_sweep_into_a_store_resumes(tmp_path):
    db = tmp_path / "s.db"
    first = quiet_sweep(N=3, e=[0.5, 0.6, 0.7], k=1e5, T=5, db=db, threads=1)
    assert first.stored_now == 3 and first.reused == 0 and not any(r.reused for r in first)
    again = quiet_sweep(N=3, e=[0.5, 0.6, 0.7, 0.8], k=1e5, T=5, db=db, threads=1)
    assert again.stored_now == 1 and again.reused == 3
    assert [r.n_coll for r in again][:3] == [r.n_coll for r in first]  # read back exactly
    assert [r.reused for r in again] == [True, True, True, False]
    assert len(granchain.Store(db).runs()) == 4  # nothing stored twice


def test_ctrl_c_stops_a_sweep_within_a_second_keeping_what_finished(tmp_path):
    # The sweep starts the longest points first: two long ones take two threads, the two short ones
    # finish on the third; then SIGINT while the long ones run. Interrupted comes within a second,
    # holding exactly the points stored.
    db = tmp_path / "s.db"
    seen = []
    with ctrl_c_after(1.5) as c:
        with pytest.raises(granchain.Interrupted) as info:
            granchain.sweep(N=25, e=[0.5, 0.9], k=1e6, T=[2, 1e6], db=db, threads=3, progress=seen.append)
    assert c.elapsed < 1.0
    done = info.value.result
    assert isinstance(done, granchain.SweepResult) and done.interrupted
    assert len(done) == 2 and all(r.parameters["T"] == 2 for r in done)
    assert sorted(granchain.Store(db).runs()["point_key"].tolist()) == sorted(r.key for r in done)
    assert seen and {"done", "total", "eta", "elapsed"} <= set(seen[-1])
    assert len(quiet_sweep(N=3, e=0.5, k=1e5, T=5)) == 1  # the module is still usable


def test_verdicts_are_warnings_once_per_kind():
    with pytest.warns(granchain.QualityWarning, match=r"^3 of 3 points: .*profile error bars"):
        s = granchain.sweep(N=25, e=[0.7, 0.8, 0.9], k=1e5, T=1, progress=False)
    assert all(r.warnings for r in s)


@pytest.mark.parametrize("kwargs,flags", [
    (dict(N=[3, 0]), ["--N", "3,0"]),
    (dict(e="0.5:2:0.5"), ["--e", "0.5:2:0.5"]),
    (dict(replicas=0), ["--replicas", "0"]),
    (dict(dt_factor=5, engine="reference"), ["--dt-factor", "5", "--engine", "reference"]),
])
def test_bad_input_is_the_clis_message_by_keyword(cli, tmp_path, kwargs, flags):
    expected = cli_error(cli("sweep", *flags, "--db", tmp_path / "x.db"))
    with pytest.raises(ValueError) as info:
        granchain.sweep(progress=False, **kwargs)
    names = [p["name"] for p in granchain.run_parameters()] + ["replicas", "threads"]
    assert str(info.value) == keyword_form(expected, names)
    assert not (tmp_path / "x.db").exists()
