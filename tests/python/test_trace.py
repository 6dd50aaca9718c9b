"""granchain.trace: the samples and events of `granchain trace`, bit for bit, interruptible."""

import csv
import io

import numpy as np
import pytest

import granchain
from conftest import cli_error, ctrl_c_after, keyword_form


@pytest.mark.parametrize("kwargs,flags", [
    (dict(N=5, e=0.7, k=1e5, t_to=3, dt=0.01, seed=2), ["--N", 5, "--e", 0.7, "--k", "1e5", "--to", 3, "--dt", 0.01, "--seed", 2]),
    (dict(N=4, e=0.3, k=1e6, setup="free", t_to=5, dt=0.05, realization=3),
     ["--N", 4, "--e", 0.3, "--k", "1e6", "--setup", "free", "--to", 5, "--dt", 0.05, "--realization", 3]),
])
def test_a_trace_is_the_clis(cli, tmp_path, kwargs, flags):
    out, events = tmp_path / "t.csv", tmp_path / "ev.csv"
    p = cli("trace", *flags, "-o", out, "--events", events)
    assert p.returncode == 0, p.stderr
    rows = list(csv.reader(io.StringIO(out.read_text())))[1:]
    tr = granchain.trace(**kwargs)
    assert tr.t.tolist() == [float(r[0]) for r in rows]
    assert tr.z.tolist() == [[float(x) for x in r[1:]] for r in rows]  # exact: 17 digits read back
    ev = list(csv.DictReader(io.StringIO(events.read_text())))
    assert len(ev) == len(tr.events.t) > 0
    assert tr.events.kind.tolist() == [e["kind"] for e in ev] and tr.events.i.tolist() == [int(e["i"]) for e in ev]
    assert "samples" in repr(tr) and len(repr(tr)) < 200


def test_ctrl_c_stops_a_trace_keeping_the_samples_recorded():
    with ctrl_c_after(1.0) as c:
        with pytest.raises(granchain.Interrupted) as info:
            granchain.trace(N=50, e=0.5, k=1e8, t_to=1e5, dt=0.1)
    assert c.elapsed < 1.0
    part = info.value.result
    assert 0 < len(part.t) < 1e6 and part.z.shape == (len(part.t), 50)
    assert np.all(np.diff(part.t) > 0) and (len(part.events.t) == 0 or part.events.t.max() <= part.t[-1])


def test_bad_input_is_the_clis_message_by_keyword(cli):
    expected = cli_error(cli("trace", "--N", 3, "--dt", 0))
    with pytest.raises(ValueError) as info:
        granchain.trace(N=3, dt=0)
    assert str(info.value) == keyword_form(expected, ["dt", "N"])
    with pytest.raises(ValueError, match=r"^t_to = 0 is out of range; valid range: t_from = 0 < t_to <= 1e15$"):
        granchain.trace(N=3, t_to=0)
    with pytest.raises(ValueError, match="trace needs a soft engine"):
        granchain.trace(N=3, engine="hard")


def test_a_traces_velocities_are_the_rate_of_change_of_its_heights():
    # One sphere between floor hits flies a parabola, whose central difference is its velocity exactly.
    h = 1e-3
    tr = granchain.trace(N=1, e=0.9, k=1e6, t_to=20, dt=h, seed=4)
    assert tr.v.shape == tr.z.shape == (len(tr.t), 1)
    hits = tr.events.t
    inner = [s for s in range(1, len(tr.t) - 1) if not np.any(np.abs(hits - tr.t[s]) < 2 * h) and tr.z[s, 0] > 0.51]
    assert len(inner) > 0.5 * len(tr.t)
    s = np.array(inner)
    central = (tr.z[s + 1, 0] - tr.z[s - 1, 0]) / (2 * h)
    assert np.max(np.abs(central - tr.v[s, 0])) < 1e-8
