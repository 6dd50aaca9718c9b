"""The closed forms from Python: values, the symmetry e_c(2N) = e_c^wall(N), ranges, the CLI's numbers."""

import math

import numpy as np
import pytest

import granchain


def test_ec_free_of_three_is_mcnamara_young():
    assert granchain.ec3() == 7 - 4 * math.sqrt(3)
    assert abs(granchain.ec_free(3) - (7 - 4 * math.sqrt(3))) < 1e-15
    assert abs(granchain.ec_free(N=3) - granchain.ec3()) < 1e-15


def test_free_space_is_the_mirror_image_of_a_wall():
    N = np.arange(2, 200)
    assert np.allclose(granchain.ec_free(2 * N), granchain.ec_wall_icw(N), rtol=0, atol=1e-14)
    assert granchain.ec_wall_icw(2) == pytest.approx(3 - 2 * math.sqrt(2), abs=1e-15)  # tan^2(pi/8)
    assert granchain.ec_wall_icw_asymptotic(N=1000) == pytest.approx(1 - math.pi / 1000)


def test_three_body_map():
    e = np.array([0.01, 0.03, 0.05])
    q = granchain.q_ratio(e)
    assert np.all((q > 0) & (q < 1))
    assert np.allclose(granchain.ntot_slope_per_ln_k(e), -1 / (2 * np.log(q)))
    assert np.allclose(granchain.collisions_slope_per_ln_k(e), 2 * granchain.ntot_slope_per_ln_k(e))
    ms, mps = granchain.m_star(e), granchain.m_prime_star(e)
    assert np.allclose(q, (ms / (e * mps)) ** 2)
    # m* and m'* are the roots of m^2 + b m + e = 0 with b = (1 + e)/2, so m* m'* e = e.
    assert np.allclose(ms * mps * e, e)
    assert granchain.cushion_Nc_wall(e=0.5) == pytest.approx(math.log(8) / 0.5)
    assert granchain.ec_wall_cushion(granchain.cushion_Nc_wall(0.5)) == pytest.approx(0.5)


def test_values_are_the_clis(cli_json):
    j = cli_json("theory", "--N", "3,25", "--e", "0.01,0.05")
    for row in j["per_N"]:
        assert granchain.ec_free(row["N"]) == row["ec_free"]
        assert granchain.ec_wall_icw(row["N"]) == row["ec_wall_icw"]
        assert granchain.ec_wall_cushion(row["N"]) == row["ec_wall_cushion"]
    for row in j["per_e"]:
        assert granchain.q_ratio(row["e"]) == row["q"]
        assert granchain.f_shift(row["e"]) == row["f"]
        assert granchain.ntot_slope_per_ln_k(row["e"]) == row["ntot_slope_per_ln_k"]


def test_outside_a_formulas_range_is_a_value_error():
    with pytest.raises(ValueError, match="e_c\\(3\\)"):
        granchain.q_ratio(0.2)
    with pytest.raises(ValueError):
        granchain.ec_free(2)
    with pytest.raises(ValueError, match="^k = -1 is out of range; valid range: k > 0$"):
        granchain.elastic_column(N=3, k=-1)


def test_elastic_column_profiles():
    T0, m, g, d = 2.0, 1.5, 0.5, 1.2
    one = granchain.elastic_column(N=1, T0=T0, m=m, g=g, d=d)
    h = T0 / (m * g)
    assert one["z_mean"].tolist() == pytest.approx([d / 2 + h])
    assert one["z_std"].tolist() == pytest.approx([h])
    assert one["K"] == T0 / 2
    assert one["floor_rate"] == pytest.approx(m * g / T0 * math.sqrt(T0 / (2 * math.pi * m)))
    col = granchain.elastic_column(N=25, k=1e12)
    assert col["i"].tolist() == list(range(1, 26)) and col["contact_end_rate"].shape == (24,)
    # Stiff spheres (overlaps of order sqrt(T0/k) negligible): gap j is exponential with mean
    # T0/W_j, W_j = m g (N - j + 1) the weight of the particles above it.
    gaps = np.diff(np.concatenate([[0.5], col["z_mean"]])) - np.r_[0, np.ones(24)]
    assert np.allclose(gaps, 1 / np.arange(25, 0, -1), rtol=1e-3)


@pytest.mark.parametrize("N", [3.9, 2.5, np.int64(2**32 + 3), 2**40, True, float("nan")])
def test_particle_numbers_are_whole_and_in_range_never_truncated_or_wrapped(N):
    with pytest.raises(ValueError, match="N = "):
        granchain.ec_free(N)
    with pytest.raises(ValueError, match="N = "):
        granchain.ec_wall_icw(N)


def test_particle_numbers_written_as_python_users_write_them():
    assert granchain.ec_free(3.0) == granchain.ec_free(3) == granchain.ec_free(np.int64(3)) == pytest.approx(granchain.ec3())
    assert list(granchain.ec_free(np.array([3, 4]))) == [granchain.ec_free(3), granchain.ec_free(4)]


def test_three_body_map_at_small_e_has_no_cancellation():
    # Eq. (def_q) as printed, q = (a - r)/(a + r), evaluated with 500 digits: in doubles a - r
    # cancels at small e; granchain's q must keep full precision there.
    import decimal
    decimal.getcontext().prec = 500
    for e in [1e-6, 1e-9, 1e-12, 1e-100]:
        E = decimal.Decimal(e)
        a = 1 - 6 * E + E * E
        r = (1 + E) * (1 - 14 * E + E * E).sqrt()
        assert granchain.q_ratio(e) == pytest.approx(float((a - r) / (a + r)), rel=1e-13)
        b = (1 + E) / 2
        assert granchain.m_star(e) == pytest.approx(float((-b + (b * b - 4 * E).sqrt()) / 2), rel=1e-13)
        assert granchain.ntot_slope_per_ln_k(e) == pytest.approx(-1 / (2 * float(((a - r) / (a + r)).ln())), rel=1e-13)
    with pytest.raises(ValueError):
        granchain.q_ratio(1e-200)
