// granchain's closed forms (theory/collapse_theory.hpp, theory/equilibrium_column.hpp) with keyword
// arguments. The collapse formulas take scalars or numpy arrays (element by element); a value
// outside a formula's range raises ValueError with the C++ message.
#include <fmt/format.h>
#include <pybind11/numpy.h>

#include <cmath>

#include "bindings.hpp"
#include "theory/collapse_theory.hpp"
#include "theory/equilibrium_column.hpp"

namespace granchain::python {

namespace {

template <class T>
py::array_t<T> array_of(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw py::value_error(what);
}

// The exact e = 1 column: profiles, floor and contact-end rates, n_coll.
py::dict elastic_column(long long N, double k, double T0, double m, double d, double g) {
  require(N >= 1 && N <= 100000, fmt::format("N = {} is out of range; valid range: integer 1 <= N <= 100000", N));
  require(k > 0 && std::isfinite(k), fmt::format("k = {} is out of range; valid range: k > 0", k));
  require(T0 > 0 && std::isfinite(T0), fmt::format("T0 = {} is out of range; valid range: T0 > 0", T0));
  require(m > 0 && std::isfinite(m), fmt::format("m = {} is out of range; valid range: m > 0", m));
  require(d > 0 && std::isfinite(d), fmt::format("d = {} is out of range; valid range: d > 0", d));
  require(g > 0 && std::isfinite(g), fmt::format("g = {} is out of range; valid range: g > 0", g));
  ChainParameters p;
  p.N = static_cast<int>(N);
  p.k = k;
  p.kT0 = T0;
  p.m = m;
  p.d = d;
  p.g = g;
  p.e = 1.0;
  const ElasticColumnEquilibrium eq = elastic_column_equilibrium(p);  // domain_error -> ValueError
  py::dict out;
  std::vector<std::int64_t> index(eq.z_mean.size());
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = static_cast<std::int64_t>(i) + 1;
  out["i"] = array_of(index);
  out["z_mean"] = array_of(eq.z_mean);
  out["z_std"] = array_of(eq.z_std);
  out["K"] = eq.kinetic;
  out["floor_rate"] = eq.floor_rate;
  out["contact_end_rate"] = array_of(eq.contact_end_rate);
  out["n_coll"] = eq.n_coll;
  return out;
}

// A formula of the particle number N, element by element over a scalar or an array: every N must
// be a whole number (3.0 is 3; 3.9 is refused, not truncated) with 1 <= N <= 1e9 (the CLI's
// `theory --N` range), so no value is silently truncated or wrapped.
template <class F>
py::object of_particle_number(F f, const char* function, const py::object& N) {
  if (PyBool_Check(N.ptr())) throw py::value_error(fmt::format("{}: N = {} is not a particle number", function, std::string(py::str(N))));
  const auto in = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(N);
  if (!in) throw py::value_error(fmt::format("{}: N = {} is not a number or an array of numbers", function, std::string(py::repr(N))));
  py::array_t<double> out(std::vector<py::ssize_t>(in.shape(), in.shape() + in.ndim()));
  const double* x = in.data();
  double* y = out.mutable_data();
  for (py::ssize_t i = 0; i < in.size(); ++i) {
    if (std::isfinite(x[i]) && x[i] != std::floor(x[i]))
      throw py::value_error(fmt::format("{}: N = {} is not a whole number; valid range: integer 1 <= N <= 1e9", function, x[i]));
    if (!(x[i] >= 1 && x[i] <= 1e9))
      throw py::value_error(fmt::format("{}: N = {} is out of range; valid range: integer 1 <= N <= 1e9", function, x[i]));
    y[i] = f(x[i]);
  }
  if (in.ndim() == 0) return py::float_(y[0]);
  return py::object(out);
}

}  // namespace

void bind_theory(py::module_& m) {
  using namespace granchain::theory;
  // e_c^wall and e_c as functions of N (integers), the rest of e.
  m.def("ec_wall_icw", [](const py::object& N) { return of_particle_number([](double n) { return ec_wall_icw(static_cast<int>(n)); }, "ec_wall_icw", N); }, py::arg("N"),
        "ICW model, Eq. (icw): e_c^wall(N) = tan^2(pi/4 (1 - 1/N)); N >= 1.");
  m.def("ec_wall_icw_asymptotic", [](const py::object& N) { return of_particle_number([](double n) { return ec_wall_icw_asymptotic(static_cast<int>(n)); }, "ec_wall_icw_asymptotic", N); }, py::arg("N"),
        "Large-N form of the ICW e_c^wall, Eq. (ec_icw_wall): 1 - pi/N; N >= 1.");
  m.def("cushion_Nc_wall", py::vectorize(&cushion_Nc_wall), py::arg("e"),
        "Cushion model: the least N that collapses on a wall at e, ln(4/(1-e))/(1-e); 0 <= e < 1.");
  m.def("ec_wall_cushion", py::vectorize(&ec_wall_cushion), py::arg("N"),
        "Cushion model's e_c^wall(N), the inverse of cushion_Nc_wall; N >= 2.");
  m.def("ec_wall_cushion_asymptotic", py::vectorize(&ec_wall_cushion_asymptotic), py::arg("N"),
        "Large-N form of the cushion e_c^wall, Eq. (ec_cushion); N >= 1.");
  m.def("ec3", &ec3, "e_c(3) = 7 - 4 sqrt(3) (McNamara & Young).");
  m.def("ec_free", [](const py::object& N) { return of_particle_number([](double n) { return ec_free(static_cast<int>(n)); }, "ec_free", N); }, py::arg("N"),
        "Free-space e_c(N) = tan^2(pi/4 (1 - 2/N)) (Sec. III.B); N >= 3, ec_free(3) = ec3().");
  m.def("m_star", py::vectorize(&m_star), py::arg("e"), "Stable fixed point m* of the three-body map, Eq. (mmdash); 1e-150 <= e <= e_c(3).");
  m.def("m_prime_star", py::vectorize(&m_prime_star), py::arg("e"), "Fixed point m'*, Eq. (mdashm); 1e-150 <= e <= e_c(3).");
  m.def("q_ratio", py::vectorize(&q_ratio), py::arg("e"), "q = (m*/(e m'*))^2, Eq. (def_q); 1e-150 <= e <= e_c(3).");
  m.def("f_shift", py::vectorize(&f_shift), py::arg("e"), "Soft-sphere shift f of Appendix B, Eq. (deltat12ss); 1e-150 <= e <= e_c(3).");
  m.def("ntot_slope_per_ln_k", py::vectorize(&ntot_slope_per_ln_k), py::arg("e"),
        "Slope of n_tot against ln k, Eq. (ntot-log): -1/(2 ln q) (times ln 10 against log10 k); 0 < e < e_c(3).");
  m.def("collisions_slope_per_ln_k", py::vectorize(&collisions_slope_per_ln_k), py::arg("e"),
        "Slope against ln k of all collisions of the three-body sequence: -1/ln q; 0 < e < e_c(3).");
  m.def("elastic_column", &elastic_column, py::kw_only(), py::arg("N") = 25, py::arg("k") = 1e5, py::arg("T0") = 1.0,
        py::arg("m") = 1.0, py::arg("d") = 1.0, py::arg("g") = 1.0,
        "Exact equilibrium of the elastic (e = 1) driven column: dict with numpy arrays i, z_mean, z_std "
        "(per particle, 1 at the bottom) and contact_end_rate (per pair), and K (= T0/2 for every particle), "
        "floor_rate, n_coll.");
}

}  // namespace granchain::python
