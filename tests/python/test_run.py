"""granchain.run: the same numbers as `granchain run`, the CLI's validation, the physics of the floor."""

import json
import os
import signal
import threading
import time
import warnings

import numpy as np
import pytest

import granchain
from conftest import cli_error, keyword_form


def same_json_but_cost(a, b):
    """Two run JSONs equal in everything but wall and CPU time, code version and the provenance's
    command line (the module's names the Python program); both provenances come from the same build."""
    assert a["provenance"]["build"] == b["provenance"]["build"]
    assert "granchain Python module" in a["provenance"]["command_line"]
    assert " run " in b["provenance"]["command_line"]
    for j in (a, b):
        j["cost"].pop("wall_seconds")
        j["cost"].pop("cpu_seconds")
        j.pop("code_version")
        j.pop("provenance")
    return a == b


@pytest.mark.parametrize("engine,params", [
    ("exact", dict(N=5, e=0.9, k=1e6, T=100, seed=7)),
    ("reference", dict(N=3, e=0.7, k=1e4, T=20, seed=3)),
    ("hard", dict(N=4, e=0.95, T=50, seed=11)),
])
def test_run_is_bit_identical_to_the_cli(cli_json, engine, params):
    r = granchain.run(engine=engine, **params)
    flags = [f"--{name}={repr(v) if isinstance(v, float) else v}" for name, v in params.items()]
    j = cli_json("run", f"--engine={engine}", *flags, "--no-db", "-q")
    assert r["n_coll"] == j["observables"]["n_coll"]["value"]
    assert r["n_coll_err"] == j["observables"]["n_coll"]["error"]
    assert r["particle_collisions"] == j["observables"]["particle_collisions"]
    assert r["floor_hits"] == j["observables"]["floor_hits"]
    assert r["stationary"] == j["stationarity"]["stationary"]
    for q in ("n_coll", "mean_height"):  # both distances of the halves check
        for z in ("z", "z_settled"):
            assert r["stationarity"][q][z] == j["stationarity"][q][z]
    assert r["z_mean"].tolist() == [p["z_mean"] for p in j["profiles"]]
    assert r["K_err"].tolist() == [p["K_err"] for p in j["profiles"]]
    assert r["parameters"]["k"] == (np.inf if engine == "hard" else params["k"])
    # The blocking curve: the reported error is one of its levels, and the CLI's JSON has the same.
    curve = r["blocking"]["n_coll"]
    assert curve["error"].tolist() == [l["error"] for l in j["blocking"]["n_coll"]]
    assert r["n_coll_err"] in curve["error"].tolist()
    assert curve["blocks"][-1] == 16 and curve["blocks"][0] == 2 * curve["blocks"][1]
    # The whole JSON the module keeps is the CLI's, number for number.
    assert same_json_but_cost(json.loads(r["json"]), j)


def test_numbers_and_text_give_the_same_run():
    a = granchain.run(N=3, e=0.8, k=1e5, T=30, seed=2)
    b = granchain.run(N="3", e="0.8", k="1e5", T="30", seed="2")
    c = granchain.run(N=np.int64(3), e=np.float64(0.8), k=1e5, T=30.0, seed=2)
    assert a["n_coll"] == b["n_coll"] == c["n_coll"]
    assert a["z_std"].tolist() == b["z_std"].tolist() == c["z_std"].tolist()


def test_numbers_as_python_users_write_them_give_the_same_run():
    # A whole float for an integer parameter, numpy scalars of any width and 0-d arrays are the
    # numbers they hold; a fraction for an integer parameter is still refused.
    a = granchain.run(N=3, e=0.8, k=1e5, T=30, seed=2)
    d = granchain.run(N=3.0, e=np.array(0.8), k=np.float32(1e5), T=np.array(30), seed=np.int32(2))
    assert a["n_coll"] == d["n_coll"]
    assert a["z_std"].tolist() == d["z_std"].tolist()
    for bad in (2.5, np.array(2.5), np.float64(3.5)):
        with pytest.raises(ValueError, match="is not an integer"):
            granchain.run(N=bad, T=5)


def test_defaults_are_the_clis():
    r = granchain.run(N=2, T=10)
    p = r["parameters"]
    assert (p["e"], p["k"], p["T0"], p["seed"], p["engine"], p["bins"]) == (0.9, 1e5, 1.0, 1, "exact", 1024)
    assert p["transient"] == 1.0  # T / 10
    assert r["i"].tolist() == [1, 2] and r["z_mean"].shape == (2,)
    assert r["stored"] is None


def test_single_particle_on_the_thermal_floor():
    # N = 1 samples the Boltzmann measure above the floor: the gap s = z - d/2 is exponential with
    # mean T0/(m g), so <z> = d/2 + T0/(m g), sigma = T0/(m g), K = T0/2 (docs/model.md).
    T0, m, g, d = 2.0, 1.5, 0.5, 1.2
    r = granchain.run(N=1, T0=T0, m=m, g=g, d=d, T=20000, seed=5)
    h = T0 / (m * g)
    assert abs(r["z_mean"][0] - (d / 2 + h)) < 4 * r["z_mean_err"][0]
    assert abs(r["z_std"][0] - h) < 4 * r["z_std_err"][0]
    assert abs(r["K"][0] - T0 / 2) < 4 * r["K_err"][0]
    theory = granchain.elastic_column(N=1, T0=T0, m=m, g=g, d=d)
    assert abs(r["floor_rate"] - theory["floor_rate"]) < 4 * r["floor_rate_err"]
    assert r["z_mean_err"][0] < 0.02 * h  # a real test, not a wide error bar


def test_elastic_column_agrees_with_its_exact_equilibrium():
    r = granchain.run(N=3, e=1.0, k=1e4, T=4000, seed=9)
    eq = granchain.elastic_column(N=3, k=1e4)
    assert np.all(np.abs(r["z_mean"] - eq["z_mean"]) < 4.5 * r["z_mean_err"])
    assert np.all(np.abs(r["z_std"] - eq["z_std"]) < 4.5 * r["z_std_err"])
    assert abs(r["n_coll"] - eq["n_coll"]) < 4.5 * r["n_coll_err"]


@pytest.mark.parametrize("kwargs,flags", [
    (dict(N=0), ["--N=0"]),
    (dict(N=2.5), ["--N=2.5"]),
    (dict(e=1.5), ["--e=1.5"]),
    (dict(k=-1), ["--k=-1"]),
    (dict(k="abc"), ["--k=abc"]),
    (dict(k=float("inf")), ["--k=inf"]),
    (dict(k=1e300), ["--k=1e+300"]),
    (dict(T0=0), ["--T0=0"]),
    (dict(bins=100), ["--bins=100"]),
    (dict(dt_factor=5), ["--dt-factor=5"]),
    (dict(engine="rk4"), ["--engine=rk4"]),
    (dict(engine="hard", k=1e6), ["--engine=hard", "--k=1000000.0"]),
    (dict(tc=1e-6), ["--tc=1e-06"]),
    (dict(T=0.001), ["--T=0.001"]),
    (dict(m=1e-300), ["--m=1e-300"]),
    (dict(engine="reference", audit=True), ["--engine=reference", "--audit"]),
])
def test_bad_input_raises_value_error_with_the_clis_message(cli, kwargs, flags):
    with pytest.raises(ValueError) as info:
        granchain.run(**kwargs)
    expected = cli_error(cli("run", *flags, "--no-db"))
    # The CLI's message, each parameter named by its keyword (e, dt_factor) instead of its flag.
    names = [q["name"] for q in granchain.run_parameters()] + ["audit"]
    assert str(info.value) == keyword_form(expected, names)
    assert "--" not in str(info.value)
    assert "valid" in expected or "leave --k out" in expected or "belongs to" in expected or "audit" in expected


def test_messages_name_the_parameter_and_its_range():
    with pytest.raises(ValueError, match=r"^e = 1.5 is out of range; valid range: 0 < e <= 1$"):
        granchain.run(e=1.5)
    with pytest.raises(ValueError, match=r"^sample_interval = -1 is out of range"):
        granchain.run(sample_interval=-1)
    with pytest.raises(TypeError):
        granchain.run(n=3)  # not a parameter: Python's own error


def test_stored_run_is_in_the_store(tmp_path):
    db = tmp_path / "r.db"
    r = granchain.run(N=2, T=20, seed=4, db=db)
    assert r["stored"]["run_id"] == 1 and json.loads(r["json"])["stored"]["run_id"] == 1
    rows = granchain.Store(db).runs()
    assert rows["n_coll"].tolist() == [r["n_coll"]] and rows["seed"].tolist() == [4]
    with pytest.raises(ValueError, match="^db: "):
        granchain.run(N=2, T=1, db=tmp_path / "no-such-folder" / "x.db")


def test_progress_callback_and_its_exception_end_the_run():
    seen = []

    def stop(p):
        seen.append(p)
        raise KeyError("stop here")

    # A run of many seconds, ended by the first progress report after half a second.
    t0 = time.monotonic()
    with pytest.raises(KeyError, match="stop here"):
        granchain.run(N=25, e=0.9, k=1e6, T=1e6, progress=stop)
    assert time.monotonic() - t0 < 5
    assert len(seen) == 1 and 0 < seen[0]["t"] < seen[0]["t_total"] == 1.1e6


def test_ctrl_c_stops_a_run():
    # SIGINT during a run of many seconds: KeyboardInterrupt within about half a second. Python's
    # handler is installed for the test (a shell's background job starts with SIGINT ignored), and
    # a progress callback bounds the run should the signal never arrive.
    def too_long(p):
        if p["wall_seconds"] > 20:
            raise TimeoutError("no KeyboardInterrupt")

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.monotonic()
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            granchain.run(N=25, e=0.9, k=1e6, T=1e6, progress=too_long)
    finally:
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - t0 < 5
    assert granchain.run(N=2, T=10)["n_coll"] > 0  # the module is still usable


def test_runs_release_the_gil():
    # While a run computes in a thread, the main thread keeps running Python.
    result = {}
    worker = threading.Thread(target=lambda: result.update(granchain.run(N=25, e=0.9, k=1e6, T=1500, seed=1)))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    assert result["n_coll"] > 0
    assert ticks >= 20, f"the main thread ran only {ticks} times during the run: is the GIL held?"


def test_concurrent_runs_give_the_serial_numbers():
    specs = [dict(N=6, e=0.85, k=1e6, T=100, seed=s) for s in (1, 2, 3)]
    serial = [granchain.run(**s)["n_coll"] for s in specs]
    out = [None] * len(specs)

    def work(i):
        out[i] = granchain.run(**specs[i])["n_coll"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(specs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert out == serial


def test_a_stored_run_is_read_back_not_stored_twice(tmp_path):
    # The CLI's rule: the same parameters and seed are the same trajectory; a repeated call (a
    # re-executed notebook cell, a loop without seeds) reads it back with a warning.
    db = tmp_path / "r.db"
    first = granchain.run(N=2, T=20, seed=4, db=db)
    assert first["reused"] is False
    with pytest.warns(UserWarning, match="is this run already"):
        again = granchain.run(N=2, T=20, seed=4, db=db)
    assert again["reused"] is True and again["stored"]["run_id"] == first["stored"]["run_id"]
    assert again["n_coll"] == first["n_coll"]
    assert len(granchain.Store(db).runs()) == 1
    granchain.run(N=2, T=20, seed=5, db=db)  # a replica on purpose: another seed
    assert len(granchain.Store(db).runs()) == 2


def test_quality_verdicts_are_warnings_and_in_the_json(cli_json):
    # A window of one time unit: not stationary and no plateau for any profile error. The module
    # raises each verdict of the command's JSON as a QualityWarning, in the same words.
    expected = cli_json("run", "--N", 25, "--T", 1, "--no-db")["warnings"]
    assert len(expected) == 2 and "not stationary" in expected[0] and "75 of 75 profile error bars" in expected[1]
    with pytest.warns(granchain.QualityWarning) as caught:
        r = granchain.run(N=25, T=1)
    assert [str(w.message) for w in caught] == expected == r.warnings
    assert json.loads(r.json)["warnings"] == expected
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a run without reservations warns of nothing
        assert granchain.run(N=3, e=0.9, k=1e5, T=2000, transient=100).warnings == []


def test_a_result_reads_as_a_notebook_expects():
    r = granchain.run(N=3, e=0.9, k=1e5, T=2000, transient=100)
    assert isinstance(r, dict) and r.n_coll == r["n_coll"] and r.parameters.N == 3 and r.cost.events > 0
    text = repr(r)
    assert len(text) < 200 and text.startswith("RunResult(N=3, e=0.9") and "n_coll = " in text
    prof = r.profile()
    assert prof.dtype.names == granchain.RunResult.PROFILE_FIELDS and prof["i"].tolist() == [1, 2, 3]
    assert prof["K"].tolist() == r.K.tolist()
    with pytest.raises(AttributeError, match="no field 'ncoll'"):
        r.ncoll
    row = r.scalars()
    assert row["N"] == 3 and row["n_coll"] == r.n_coll and "json" not in row
    pd = pytest.importorskip("pandas")
    frame = r.to_pandas()
    assert isinstance(frame, pd.DataFrame) and frame.index.name == "i" and frame["z_mean"].tolist() == r.z_mean.tolist()


def test_contact_durations_per_pair():
    """A contact of the fluid column lasts about tau_c; the dict's arrays are the JSON's, per pair."""
    r = granchain.run(N=10, e=0.95, k=1e4, T=200)
    c = r["contacts"]
    assert len(c["mean"]) == 10 and c["contacts"][0] == 0  # pair 0: the thermal floor has no contacts
    busy = c["contacts"] >= 20
    assert busy.any()
    assert np.all(np.abs(c["mean"][busy] - 1.0) < 0.2)
    pairs = json.loads(r["json"])["contacts"]["pairs"]
    assert [p["contacts"] for p in pairs] == list(c["contacts"].astype(int))
    first, hist = c["histogram"][1]
    assert sum(hist) == c["contacts"][1] and first == pairs[1]["first_bin"]
    assert "contacts" not in granchain.run(N=5, engine="hard", T=20)
