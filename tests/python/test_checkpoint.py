"""Checkpoints from Python: run(checkpoint=...) and sweep(checkpoint_dir=...) save their state on
Ctrl-C, and the same call resumes it to the uninterrupted run's numbers, bit for bit."""

import numpy as np
import pytest

import granchain
from conftest import cli_error, ctrl_c_after, keyword_form


def same_numbers(a, b):
    """Every measured number of two runs equal: rates, counts, errors, profiles, contacts."""
    for key in ("n_coll", "n_coll_err", "floor_rate", "pp_rate", "particle_collisions", "floor_hits"):
        assert a[key] == b[key], key
    for key in ("z_mean", "z_mean_err", "z_std", "K", "K_err"):
        assert np.array_equal(a[key], b[key]), key
    assert a["stationarity"] == b["stationarity"]
    assert a["cost"]["events"] == b["cost"]["events"] and a["cost"]["steps"] == b["cost"]["steps"]
    if "contacts" in a:
        for key in ("contacts", "mean", "longest", "contact_fraction"):
            assert np.array_equal(a["contacts"][key], b["contacts"][key]), key


# A run of a few seconds on either engine, stopped by Ctrl-C after half a second.
RUN = dict(N=20, e=0.5, k=1e6, transient=20, seed=3)


@pytest.mark.filterwarnings("ignore::granchain.QualityWarning")  # short windows: the numbers are compared, not trusted
@pytest.mark.parametrize("engine,T", [("reference", 600), ("exact", 1500)])
def test_ctrl_c_saves_a_run_and_the_same_call_resumes_it_bit_for_bit(tmp_path, engine, T):
    whole = granchain.run(engine=engine, T=T, **RUN)
    path = tmp_path / "run.ckpt"
    with ctrl_c_after(0.5) as c:
        with pytest.raises(KeyboardInterrupt, match=r"^the run's state at t = \S+ of \S+ is saved in .*run\.ckpt; the same call resumes it"):
            granchain.run(engine=engine, T=T, checkpoint=path, **RUN)
    assert c.elapsed < 2.0 and path.exists()
    reports = []  # the resumed run reports from where it went on (a fresh start's first report, 0.5 s in, lies before)
    resumed = granchain.run(engine=engine, T=T, checkpoint=path, progress=lambda p: reports.append(p["t"]), **RUN)
    assert 0 < resumed.resumed_at < T + RUN["transient"]
    assert reports and min(reports) > resumed.resumed_at
    same_numbers(resumed, whole)
    assert not path.exists()  # spent once the result is returned
    assert granchain.run(engine=engine, T=1, checkpoint=path, **RUN).resumed_at is None  # a fresh start


def test_a_checkpoint_of_a_stored_run_is_removed_and_the_run_read_back(tmp_path):
    db, path = tmp_path / "r.db", tmp_path / "run.ckpt"
    with ctrl_c_after(0.5):
        with pytest.raises(KeyboardInterrupt):
            granchain.run(engine="reference", T=600, checkpoint=path, db=db, **RUN)
    stored = granchain.run(engine="reference", T=600, db=db, **RUN)  # the same run, without the checkpoint
    with pytest.warns(UserWarning) as seen:
        back = granchain.run(engine="reference", T=600, db=db, checkpoint=path, **RUN)
    assert any("held the state of this stored run; it was removed" in str(w.message) for w in seen)
    assert back.reused and back.n_coll == stored.n_coll and not path.exists()


def stop_at_first_report(p):
    raise KeyboardInterrupt  # as Ctrl-C while a progress callback runs


def test_a_checkpoint_of_another_run_is_refused_and_kept(tmp_path):
    path = tmp_path / "run.ckpt"
    with pytest.raises(KeyboardInterrupt, match=r"^the run's state at t = \S+ of 620 is saved in"):
        granchain.run(engine="reference", T=600, checkpoint=path, progress=stop_at_first_report, **RUN)
    saved = path.read_bytes()
    with pytest.raises(ValueError, match=r"^checkpoint: '.*run\.ckpt' holds the state of another run \(.*seed=3\); give another file"):
        granchain.run(engine="reference", T=600, checkpoint=path, **dict(RUN, seed=4))
    assert path.read_bytes() == saved


def test_ctrl_c_saves_a_sweeps_running_points_and_the_same_call_resumes_them(tmp_path):
    grid = dict(N=20, e=[0.5, 0.6], k=1e6, T=3000, transient=20, engine="exact", threads=2)
    whole = granchain.sweep(progress=False, **grid)
    db, states = tmp_path / "s.db", tmp_path / "states"
    with pytest.raises(granchain.Interrupted, match=r"the states of 2 running points are saved in .*states") as info:
        granchain.sweep(db=db, checkpoint_dir=states, progress=stop_at_first_report, **grid)
    cut = info.value.result
    assert cut.saved == 2 and len(cut) == 0 and len(list(states.iterdir())) == 2
    again = granchain.sweep(db=db, checkpoint_dir=states, progress=False, **grid)
    assert again.resumed == 2 and again.saved == 0 and again.stored_now == 2
    assert all(0 < r.resumed_at < 3020 for r in again)  # each point says where it went on from
    assert all(r.resumed_at is None for r in whole)  # fresh starts
    for a, b in zip(again, whole):
        same_numbers(a, b)
    back = granchain.sweep(db=db, checkpoint_dir=states, progress=False, **grid)
    assert back.reused == 2 and all(r.reused and r.resumed_at is None for r in back)  # read back from the store
    assert list(states.iterdir()) == []  # each state removed once its point is stored


@pytest.mark.parametrize("command,kwargs,flags", [
    ("run", dict(checkpoint_every=10), ["--checkpoint-every", "10"]),
    ("run", dict(checkpoint=""), ["--checkpoint", ""]),
    ("sweep", dict(checkpoint_every=10), ["--checkpoint-every", "10"]),
    ("sweep", dict(checkpoint_dir="d", checkpoint_every=0.5), ["--checkpoint-dir", "d", "--checkpoint-every", "0.5"]),
])
def test_bad_checkpoint_input_is_the_clis_message_by_keyword(cli, tmp_path, command, kwargs, flags):
    expected = cli_error(cli(command, "--N", "3", "--T", "1", *flags, "--db", tmp_path / "x.db", cwd=tmp_path))
    with pytest.raises(ValueError) as info:
        if command == "run":
            granchain.run(N=3, T=1, db=tmp_path / "x.db", **kwargs)
        else:
            granchain.sweep(N=3, T=1, db=tmp_path / "x.db", progress=False, **kwargs)
    names = [p["name"] for p in granchain.run_parameters()] + ["checkpoint-dir"]
    assert str(info.value) == keyword_form(expected, names)
    assert not (tmp_path / "x.db").exists() and not (tmp_path / "d").exists()
