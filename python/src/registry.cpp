// The method registry, coefficient tables and the stability matrix S(V, z), from the runtime.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>

#include "bindings.hpp"
#include "erkn/method.hpp"
#include "erkn/stability.hpp"

namespace erkn::python {
namespace {

// The fields of `erkn list --json` (python/tests/test_registry.py compares the two).
py::dict describe(const Method& m) {
  py::dict d;
  d["name"] = std::string(m.name());
  d["kind"] = std::string(m.kind_name());
  d["stages"] = m.stages();
  d["order"] = m.order();
  d["generalized_order"] =
      std::vector<int>(m.generalized_order().begin(), m.generalized_order().end());
  // NaN (no failing condition checked) is None, as `erkn list --json` writes null.
  const auto constant = [](double x) -> py::object {
    return std::isnan(x) ? py::object(py::none()) : py::object(py::float_(x));
  };
  d["error_constant"] = constant(m.error_constant());
  py::list generalized_constants;
  for (double x : m.generalized_error_constant()) generalized_constants.append(constant(x));
  d["generalized_error_constant"] = generalized_constants;
  d["poles"] = std::vector<double>(m.poles().begin(), m.poles().end());
  d["modified"] = std::vector<double>(m.modified().begin(), m.modified().end());
  d["processed"] = m.is_processed();  // (psi = pi o K o pi^-1: order is psi's)
  d["kernel_order"] = m.kernel_order();
  d["source"] = std::string(m.reference());
  d["paper"] = m.from_paper();
  d["id"] = std::string(m.id_name());
  return d;
}

// {"method", "stages", "order", "v", "c", "d", "b", "bbar", "abar" (s x s, lower triangular)}.
py::dict tableau(const std::string& name, double v) {
  const Method& m = Method::by_name(name);
  const Coefficients k = m.at(v);
  const int s = m.stages();
  Eigen::MatrixXd abar = Eigen::MatrixXd::Zero(s, s);
  Eigen::VectorXd c(s), d(s), b(s), bbar(s);
  for (int i = 0; i < s; ++i) {
    c[i] = m.table().c[i], d[i] = m.table().d[i], b[i] = k.b[i], bbar[i] = k.bbar[i];
    for (int j = 0; j <= i; ++j) abar(i, j) = k.abar(i, j);
  }
  py::dict t;
  t["method"] = std::string(m.name());
  t["stages"] = s;
  t["order"] = m.order();
  t["v"] = v;
  t["c"] = c, t["d"] = d, t["b"] = b, t["bbar"] = bbar, t["abar"] = abar;
  if (m.has_modified_kicks())
    t["modified"] = std::vector<double>(m.modified().begin(), m.modified().end());
  if (m.is_processed()) {  // (as erkn tableau prints it: the kernel's order and pi^-1)
    const generated::Table& p = m.table();
    t["kernel_order"] = m.kernel_order();
    t["pre_drift"] = std::vector<double>(p.pre_drift, p.pre_drift + p.npre + 1);
    t["pre_kick"] = std::vector<double>(p.pre_kick, p.pre_kick + p.npre);
    t["pre_modified"] = std::vector<double>(p.pre_modified, p.pre_modified + p.npre);
  }
  return t;
}

// S(V_k, z_k) for paired flat arrays: (S with shape (n, 2, 2) row-major, class names).
py::tuple stability(const std::string& name, const Eigen::Ref<const Eigen::VectorXd>& V,
                    const Eigen::Ref<const Eigen::VectorXd>& z) {
  const Method& m = Method::by_name(name);
  py::array_t<double> S({V.size(), Eigen::Index(2), Eigen::Index(2)});
  auto s = S.mutable_unchecked<3>();
  std::vector<std::string> classes;
  for (Eigen::Index k = 0; k < V.size(); ++k) {
    StabilityMatrix x{};
    StabilityClass cls = StabilityClass::pole;
    if (m.kind() == Kind::rkn || m.pole_within(V[k], 1e-6) < 0) {
      x = stability_matrix(m, V[k], z[k]);
      cls = classify(x);
    } else {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      x = {nan, nan, nan, nan};
    }
    s(k, 0, 0) = x.s11, s(k, 0, 1) = x.s12, s(k, 1, 0) = x.s21, s(k, 1, 1) = x.s22;
    classes.emplace_back(to_string(cls));
  }
  return py::make_tuple(S, classes);
}

}  // namespace

void bind_registry(py::module_& m) {
  m.def(
      "methods",
      [] {
        py::list out;
        for (const Method& method : Method::all()) out.append(describe(method));
        return out;
      },
      "every generated method as a dict with the fields of `erkn list --json`: name, kind "
      "(explicit, erkn, rkn), stages, order, generalized_order, error_constant, "
      "generalized_error_constant (None: no failing condition checked), poles, modified (the "
      "modified-kick coefficients e_i; empty for plain kicks), source, paper, id");
  m.def(
      "load_methods",
      [](const std::string& path) {
        py::list out;
        for (const Method& method : Method::load(path)) out.append(describe(method));
        return out;
      },
      py::arg("path"),
      "adds the explicit methods of a file written by `erkn-generate --json` to the registry "
      "(erkn.methods(), method=NAME everywhere), after checking the orders they claim against "
      "the order conditions; erkn.Error names the failing condition and adds none of them. "
      "Returns their dicts (the fields of erkn.methods())");
  m.def("tableau", &tableau, py::arg("name"), py::arg("v") = 0.0,
        "coefficients of a method at v = h^2 lambda >= 0 (erkn.Error at a pole); a processed "
        "method's also kernel_order and its pre-processor pi^-1 (pre_drift, pre_kick, "
        "pre_modified)");
  m.def("_stability", &stability, py::arg("name"), py::arg("V"), py::arg("z"));
  m.attr("trace_tolerance") = kTraceTolerance;
}

}  // namespace erkn::python
