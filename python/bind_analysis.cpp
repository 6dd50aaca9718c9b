// The analysis of a count against k (analysis/asymptotic_forms.hpp) for numbers a notebook holds:
// the five candidate asymptotic forms compared by AICc and BIC, the local exponents and their trend.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>

#include "analysis/asymptotic_forms.hpp"
#include "bindings.hpp"

namespace granchain::python {

namespace {

std::vector<double> as_vector(const py::handle& x, const char* name) {
  try {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(x);
    if (!a || a.ndim() != 1) throw std::invalid_argument("");
    return {a.data(), a.data() + a.size()};
  } catch (const std::exception&) {
    throw py::value_error(std::string(name) + " must be a one-dimensional sequence of numbers");
  }
}

// k, y and either error (independent points) or covariance (an n x n matrix).
py::dict compare_forms(const py::object& k_in, const py::object& y_in, const py::object& error, const py::object& covariance) {
  const std::vector<double> k = as_vector(k_in, "k"), y = as_vector(y_in, "y");
  if (y.size() != k.size()) throw py::value_error("k and y must have the same length");
  const auto n = static_cast<Eigen::Index>(k.size());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  if (error.is_none() == covariance.is_none()) throw py::value_error("give either error (independent points) or covariance");
  if (!error.is_none()) {
    const std::vector<double> e = as_vector(error, "error");
    if (e.size() != k.size()) throw py::value_error("error must have the length of k");
    for (Eigen::Index i = 0; i < n; ++i) C(i, i) = e[static_cast<std::size_t>(i)] * e[static_cast<std::size_t>(i)];
  } else {
    const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(covariance);
    if (!c || c.ndim() != 2 || c.shape(0) != n || c.shape(1) != n) throw py::value_error("covariance must be an n x n matrix, n = len(k)");
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) C(i, j) = c.at(i, j);
  }
  analysis::FormComparison r;
  try {
    r = analysis::compare_asymptotic_forms(k, y, C);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  py::list fits;
  for (const auto& f : r.fits) {
    py::dict d;
    d["name"] = analysis::form_name(f.form);
    d["formula"] = analysis::form_formula(f.form);
    d["param"] = f.param;
    d["error"] = f.error;
    d["chi2"] = f.chi2;
    d["dof"] = f.dof;
    d["chi2_z"] = f.chi2_z;
    d["aicc"] = f.aicc;
    d["bic"] = f.bic;
    d["weight"] = f.akaike_weight;
    d["model"] = f.model;
    d["pulls"] = f.pulls;
    fits.append(d);
  }
  py::dict out;
  out["fits"] = fits;
  out["best_aicc"] = analysis::form_name(r.fits[static_cast<std::size_t>(r.best_aicc)].form);
  out["best_bic"] = analysis::form_name(r.fits[static_cast<std::size_t>(r.best_bic)].form);
  return out;
}

py::dict local_exponents(const py::object& k_in, const py::object& y_in, const py::object& err_in) {
  const std::vector<double> k = as_vector(k_in, "k"), y = as_vector(y_in, "y"), err = as_vector(err_in, "error");
  if (y.size() != k.size() || err.size() != k.size()) throw py::value_error("k, y and error must have the same length");
  std::vector<analysis::DataPoint> pts;
  for (std::size_t i = 0; i < k.size(); ++i) pts.push_back({k[i], y[i], err[i]});
  const std::vector<analysis::LocalExponent> l = analysis::local_exponents(pts);
  std::vector<double> k1, k2, a, e;
  for (const auto& x : l) k1.push_back(x.k1), k2.push_back(x.k2), a.push_back(x.alpha), e.push_back(x.error);
  const analysis::SlopeTrend t = analysis::slope_trend(l);
  py::dict out;
  out["k1"] = k1;
  out["k2"] = k2;
  out["alpha"] = a;
  out["error"] = e;
  out["mean"] = t.mean;
  out["mean_error"] = t.mean_error;
  out["constant_chi2"] = t.constant_chi2;
  out["constant_dof"] = t.constant_dof;
  out["slope_per_decade"] = t.slope;
  out["slope_error"] = t.slope_error;
  return out;
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def("compare_forms", &compare_forms, py::kw_only(), py::arg("k"), py::arg("y"), py::arg("error") = py::none(),
        py::arg("covariance") = py::none(),
        "Fit y(k) by the power law c k^alpha, a + b ln k, a + b ln k + c (ln k)^2 and c k^alpha (ln k)^beta, by generalised "
        "least squares with the points' errors (independent) or covariance; every form's chi^2 on y, AICc, BIC and Akaike "
        "weights (docs/analysis.md). Needs k > 1, y > 0 and at least 4 points.");
  m.def("local_exponents", &local_exponents, py::kw_only(), py::arg("k"), py::arg("y"), py::arg("error"),
        "d ln y / d ln k between successive k with errors from the two points (independent), and their trend: weighted mean "
        "(one power law) with its chi^2, and the slope per decade of k.");
}

}  // namespace granchain::python
