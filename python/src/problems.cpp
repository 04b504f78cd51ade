// erkn.problems: the problems library's definitions (problems/, shared with the C++ tests,
// benchmarks and experiments) bound as they are: M, the gradient, potential and Hessian in C++
// (a System that steps without the GIL), the initial data, the invariants and the exact solution.
#include "erkn/problems.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <stdexcept>

#include "bindings.hpp"
#include "erkn/error.hpp"
#include "system.hpp"

namespace erkn::python {
namespace {

using problems::Problem;

// A constructor whose std::invalid_argument arrives as erkn.Error.
template <class... Args>
auto checked(Problem (*make)(Args...)) {
  return [make](Args... args) {
    try {
      return make(args...);
    } catch (const std::invalid_argument& e) {
      throw Error(e.what());
    }
  };
}

// Each invariant at each row of Q, P (n x d): {name: (n,) array}.
py::dict invariants(const Problem& p, const Eigen::MatrixXd& Q, const Eigen::MatrixXd& P) {
  if (Q.cols() != p.dim() || P.rows() != Q.rows() || P.cols() != Q.cols())
    throw Error("invariants: q and p must both have shape (n, " + std::to_string(p.dim()) + ")");
  py::dict out;
  for (const problems::Invariant& inv : problems::invariants(p)) {
    Eigen::VectorXd values(Q.rows());
    for (Eigen::Index i = 0; i < Q.rows(); ++i)
      values[i] = inv.value(Q.row(i).transpose(), P.row(i).transpose());
    out[py::str(inv.name)] = values;
  }
  return out;
}

Eigen::MatrixXd exact(const Problem& p, const Eigen::VectorXd& t) {
  if (!p.exact) throw Error(p.title + " has no exact solution in erkn");
  Eigen::MatrixXd q(t.size(), p.dim());
  for (Eigen::Index i = 0; i < t.size(); ++i) q.row(i) = (*p.exact)(t[i]).transpose();
  return q;
}

// A problem's System with the M erkn.solve was given (its own, unless the caller changes it).
PySystem with_stiffness(const PySystem& s, const Stiffness& M, Eigen::Index d) {
  if (d != s.d)
    throw Error("this erkn.System (" + s.description + ") has dimension " + std::to_string(s.d) +
                "; q0 has " + std::to_string(d));
  PySystem out = s;
  out.system.M = M;
  return out;
}

}  // namespace

void bind_problems(py::module_& m) {
  py::class_<Problem>(m, "_Problem")
      .def_readonly("key", &Problem::key)
      .def_readonly("title", &Problem::title)
      .def_readonly("q0", &Problem::q0)
      .def_readonly("p0", &Problem::p0)
      .def_readonly("t_error", &Problem::t_error)
      .def_property_readonly("M", [](const Problem& p) { return problems::stiffness(p.M); })
      .def_property_readonly("system",
                             [](const Problem& p) {
                               return PySystem{problems::system(p), p.dim(), false, p.title};
                             })
      .def_property_readonly("exact_invariants",
                             [](const Problem& p) {
                               std::vector<std::pair<std::string, bool>> out;
                               for (const auto& inv : problems::invariants(p))
                                 out.emplace_back(inv.name, inv.exact);
                               return out;
                             })
      .def_property_readonly("has_exact", [](const Problem& p) { return bool(p.exact); })
      .def("invariants", &invariants, py::arg("q"), py::arg("p"))
      .def("exact", &exact, py::arg("t"));
  m.def("_with_stiffness", &with_stiffness, py::arg("system"), py::arg("M"), py::arg("d"));
  m.def("_fpu", checked(&problems::fpu), py::arg("m"), py::arg("omega"));
  m.def("_henon_heiles", checked(&problems::henon_heiles), py::arg("energy"));
  m.def("_sine_gordon", checked(&problems::sine_gordon), py::arg("n"), py::arg("kappa"));
  m.def("_duffing", checked(&problems::duffing), py::arg("k"));
  m.def("_stellar_orbits", checked(&problems::stellar_orbits), py::arg("eps"));
  m.def("_klein_gordon", checked(&problems::klein_gordon), py::arg("n"), py::arg("dims"));
  m.def("_sine_gordon_2d", checked(&problems::sine_gordon_2d), py::arg("n"));
}

}  // namespace erkn::python
