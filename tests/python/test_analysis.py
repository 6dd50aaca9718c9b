"""The asymptotic forms and local exponents from Python: a count drawn from each form is recognised,
the power law's exponent comes back, a drift of the local exponent shows, bad input is refused."""

import numpy as np
import pytest

import granchain

K = 10.0 ** np.arange(4, 14)


def noisy(y, rel, seed):
    rng = np.random.default_rng(seed)
    return y * (1 + rel * rng.standard_normal(y.size)), rel * y


def test_power_law_is_recognised_and_its_exponent_returned():
    y, err = noisy(3.0 * K ** 0.2, 0.01, 1)
    r = granchain.compare_forms(k=K, y=y, error=err)
    assert [f["name"] for f in r["fits"]] == ["power law", "a + b ln k", "a + b ln k + c (ln k)^2", "power law with log", "power of ln k"]
    power = r["fits"][0]
    assert r["best_aicc"] == "power law"
    assert abs(power["param"][1] - 0.2) < 4 * power["error"][1]
    assert sum(f["weight"] for f in r["fits"]) == pytest.approx(1.0)
    assert len(power["pulls"]) == K.size


def test_power_law_with_log_correction_and_covariance():
    y0 = 30 * K ** 0.25 * np.log(K) ** -1.5
    y, err = noisy(y0, 0.01, 2)
    r = granchain.compare_forms(k=K, y=y, covariance=np.diag(err ** 2))
    assert r["best_aicc"] == "power law with log"
    same = granchain.compare_forms(k=K, y=y, error=err)
    assert same["fits"][3]["chi2"] == pytest.approx(r["fits"][3]["chi2"], rel=1e-12)


def test_local_exponents_of_a_logarithm_fall():
    y, err = noisy(10 + 20 * np.log(K), 0.001, 3)
    l = granchain.local_exponents(k=K, y=y, error=err)
    assert len(l["alpha"]) == K.size - 1
    assert np.all(np.diff(l["alpha"]) < 0)  # 1 / ln k falls
    assert l["slope_per_decade"] < -5 * l["slope_error"]


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="either error"):
        granchain.compare_forms(k=K, y=K)
    with pytest.raises(ValueError, match="at least 4 points"):
        granchain.compare_forms(k=K[:3], y=K[:3], error=K[:3] * 0.01)
    with pytest.raises(ValueError, match="positive"):
        granchain.compare_forms(k=K, y=-K, error=K * 0.01)
