// The step-size advisor (erkn/advisor.hpp): advise_step_size with its findings and report, and
// the Hessian bounds it takes, at a state or along a pilot run; the accuracy-driven choice of
// method and step (erkn/accuracy.hpp) behind erkn.solve(..., tol=).
#include "erkn/advisor.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "erkn/accuracy.hpp"
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

py::list findings(const std::vector<AdvisorFinding>& all) {
  py::list out;
  for (const AdvisorFinding& f : all) out.append(finding(f));
  return out;
}

// erkn::TrialRun as a dict; None when no trial ran.
py::object trial(const TrialRun& t) {
  if (t.steps == 0 && t.failure.empty()) return py::none();
  py::dict d;
  d["steps"] = t.steps, d["error"] = t.error, d["early"] = t.early;
  d["predicted"] = t.predicted, d["horizon"] = t.horizon, d["limit"] = t.limit;
  d["first_steps"] = t.first_steps, d["first_predicted"] = t.first_predicted;
  d["saturated"] = t.saturated;
  d["explained"] = t.explained, d["mode_rate"] = t.mode_rate, d["mode_share"] = t.mode_share;
  d["takeover"] = t.takeover, d["failure"] = t.failure, d["flagged"] = t.flagged;
  return d;
}

void bind_advice(py::module_& m) {
  py::class_<AdvisorOptions>(m, "_AdvisorOptions")
      .def(py::init<>())
      .def_readwrite("potential_degree", &AdvisorOptions::potential_degree)
      .def_readwrite("pole_margin", &AdvisorOptions::pole_margin)
      .def_readwrite("trace_tolerance", &AdvisorOptions::trace_tolerance)
      .def_readwrite("z_samples", &AdvisorOptions::z_samples)
      .def_readwrite("max_change", &AdvisorOptions::max_change)
      .def_readwrite("search_step", &AdvisorOptions::search_step)
      .def_readwrite("min_excitation", &AdvisorOptions::min_excitation)
      .def_readwrite("steps", &AdvisorOptions::steps)
      .def_readwrite("energy_tolerance", &AdvisorOptions::energy_tolerance)
      .def_readwrite("trial_steps", &AdvisorOptions::trial_steps)
      .def_readwrite("trial_margin", &AdvisorOptions::trial_margin)
      .def_readwrite("explained_margin", &AdvisorOptions::explained_margin)
      .def_readwrite("saturated_margin", &AdvisorOptions::saturated_margin)
      .def_readwrite("extended_trial_steps", &AdvisorOptions::extended_trial_steps)
      .def_readwrite("ambiguity", &AdvisorOptions::ambiguity);
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
          "findings", [](const Advice& a) { return findings(a.advice.findings); },
          "one dict per flagged eigenvalue: index, lambda, V, hazard (unstable, resonance, "
          "pole), z, trace, pole, harmonic")
      .def_property_readonly(
          "equation", [](const Advice& a) { return findings(a.advice.equation); },
          "information, not flagged: one dict per eigenvalue where the differential equation "
          "itself grows (lambda + kappa < 0), its rate mu = sqrt(-(lambda + kappa))")
      .def_property_readonly(
          "notes", [](const Advice& a) { return findings(a.advice.notes); },
          "information, not flagged: the linear model's findings the trial run shows to stay "
          "within the energy criterion (with the problem only)")
      .def_property_readonly(
          "trial", [](const Advice& a) { return trial(a.advice.trial); },
          "the trial run (with the problem): a dict of steps, first_steps, first_predicted, error, "
          "early, predicted, horizon, limit, explained, saturated, mode_rate, mode_share, "
          "takeover, failure, flagged; None without one")
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

namespace {

// erkn::Choice as the dict Solution.choice carries.
py::dict choice_dict(const Choice& c) {
  py::dict d;
  d["method"] = c.method, d["h"] = c.h, d["estimated_error"] = c.estimated_error;
  d["pilot_cpu_time"] = c.pilot_cpu, d["pilot_gradient_evaluations"] = c.pilot_gradient_evaluations;
  d["reason"] = c.reason;
  py::list candidates;
  for (const Candidate& k : c.candidates) {
    py::dict e;
    e["method"] = k.method, e["piloted"] = k.piloted, e["h"] = k.h;
    e["estimated_error"] = k.estimated_error, e["predicted_cpu_time"] = k.predicted_cpu;
    candidates.append(e);
  }
  d["candidates"] = candidates;
  return d;
}

void bind_choice(py::module_& m) {
  m.def(
      "_choose",
      [](const PySystem& s, const Eigen::VectorXd& q0, const Eigen::VectorXd& p0, double t0,
         double t1, double tol, const std::string& method, double h, double pilot_fraction,
         double safety, const Options& options) {
        AccuracyRequest r{tol, method, h, pilot_fraction, safety};
        return choice_dict(choose_method_and_step(s.system, q0, p0, t0, t1, r, options));
      },
      py::arg("system"), py::arg("q0"), py::arg("p0"), py::arg("t0"), py::arg("t1"), py::arg("tol"),
      py::arg("method"), py::arg("h"), py::arg("pilot_fraction"), py::arg("safety"),
      py::arg("options"));
}

}  // namespace

void bind_advisor(py::module_& m) {
  bind_advice(m);
  bind_choice(m);
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
  m.def(
      "_advise_problem",
      [](const std::string& method, const PySystem& s, double h, const Eigen::VectorXd& q0,
         const Eigen::VectorXd& p0, const AdvisorOptions& options) {
        const Method& me = Method::by_name(method);
        return Advice{advise_step_size(me, s.system, h, q0, p0, options), std::string(me.name())};
      },
      py::arg("method"), py::arg("system"), py::arg("h"), py::arg("q0"), py::arg("p0"),
      py::arg("options"));
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
