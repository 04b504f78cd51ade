// The step-size advisor (erkn/advisor.hpp): advise_step_size with its findings and report, and
// the Hessian bounds it takes, at a state or along a pilot run.
#include "erkn/advisor.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "system.hpp"

namespace erkn::python {
namespace {

py::dict finding(const AdvisorFinding& f) {
  py::dict d;
  d["index"] = f.index;
  d["lambda"] = f.lambda;
  d["V"] = f.V;
  d["hazard"] = std::string(to_string(f.hazard));
  d["z"] = f.z;
  d["trace"] = f.trace;
  d["pole"] = f.pole;
  d["harmonic"] = f.harmonic;
  d["rate"] = f.rate;
  return d;
}

// The advice with the method it was given for (its report names the method's poles).
struct Advice {
  StepSizeAdvice advice;
  std::string method;
};

py::tuple bounds(HessianBounds b) { return py::make_tuple(b.lo, b.hi); }

void bind_advice(py::module_& m) {
  py::class_<AdvisorOptions>(m, "_AdvisorOptions")
      .def(py::init<>())
      .def_readwrite("potential_degree", &AdvisorOptions::potential_degree)
      .def_readwrite("pole_margin", &AdvisorOptions::pole_margin)
      .def_readwrite("trace_tolerance", &AdvisorOptions::trace_tolerance)
      .def_readwrite("z_samples", &AdvisorOptions::z_samples)
      .def_readwrite("max_change", &AdvisorOptions::max_change)
      .def_readwrite("search_step", &AdvisorOptions::search_step)
      .def_readwrite("min_excitation", &AdvisorOptions::min_excitation);
  py::class_<Advice>(m, "StepSizeAdvice", "erkn::StepSizeAdvice: findings for h, a suggestion")
      .def_property_readonly("h", [](const Advice& a) { return a.advice.h; })
      .def_property_readonly("method", [](const Advice& a) { return a.method; })
      .def_property_readonly(
          "hessian", [](const Advice& a) { return bounds(a.advice.hessian); },
          "(lo, hi): the bounds on the Hessian's eigenvalues used")
      .def_property_readonly(
          "safe", [](const Advice& a) { return a.advice.safe(); },
          "True when nothing is flagged for h")
      .def_property_readonly(
          "findings",
          [](const Advice& a) {
            py::list out;
            for (const AdvisorFinding& f : a.advice.findings) out.append(finding(f));
            return out;
          },
          "one dict per flagged eigenvalue: index, lambda, V, hazard (unstable, resonance, "
          "pole), z, trace, pole, harmonic")
      .def_property_readonly(
          "equation",
          [](const Advice& a) {
            py::list out;
            for (const AdvisorFinding& f : a.advice.equation) out.append(finding(f));
            return out;
          },
          "information, not flagged: one dict per eigenvalue where the differential equation "
          "itself grows (lambda + kappa < 0), its rate mu = sqrt(-(lambda + kappa))")
      .def_property_readonly(
          "suggested_h", [](const Advice& a) { return a.advice.suggested_h; },
          "the nearest h without findings (NaN when none within max_change)")
      .def_property_readonly(
          "report", [](const Advice& a) { return a.advice.report(Method::by_name(a.method)); },
          "the human-readable account (as `erkn advise` prints it)")
      .def("__repr__", [](const Advice& a) {
        return "erkn.StepSizeAdvice(method='" + a.method + "', h=" + std::to_string(a.advice.h) +
               ", findings=" + std::to_string(a.advice.findings.size()) + ")";
      });
}

}  // namespace

void bind_advisor(py::module_& m) {
  bind_advice(m);
  m.def(
      "_advise",
      [](const std::string& method, const Eigen::VectorXd& eigenvalues, double h, double lo,
         double hi, const AdvisorOptions& options, const Eigen::VectorXd& mode_energy) {
        const Method& me = Method::by_name(method);
        return Advice{advise_step_size(me, eigenvalues, h, {lo, hi}, options, mode_energy),
                      std::string(me.name())};
      },
      py::arg("method"), py::arg("eigenvalues"), py::arg("h"), py::arg("lo"), py::arg("hi"),
      py::arg("options"), py::arg("mode_energy"));
  m.def("mode_energies", &mode_energies, py::arg("M"), py::arg("q"), py::arg("p"),
        "the state's 1/2|p|^2 + 1/2 q'Mq at each eigenvalue of M (erkn/advisor.hpp)");
  m.def(
      "_hessian_bounds_at",
      [](const PySystem& s, const Eigen::VectorXd& q) {
        return bounds(hessian_bounds_at(s.system, q));
      },
      py::arg("system"), py::arg("q"));
  m.def(
      "_hessian_bounds_along",
      [](const std::string& method, const PySystem& s, double h, const Eigen::VectorXd& q0,
         const Eigen::VectorXd& p0, long steps) {
        return bounds(hessian_bounds_along(Method::by_name(method), s.system, h, q0, p0, steps));
      },
      py::arg("method"), py::arg("system"), py::arg("h"), py::arg("q0"), py::arg("p0"),
      py::arg("steps"));
}

}  // namespace erkn::python
