// erkn.Options: erkn::Options field by field. Every assignment runs erkn::validate on a copy
// with the new value and keeps it only if that passes, so a refused value changes nothing and
// the error is C++'s, naming the field.
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "erkn/integrator.hpp"

namespace erkn::python {
namespace {

template <class T>
void field(py::class_<Options>& c, std::vector<std::string>& names, const char* name,
           T Options::*member, const char* doc) {
  names.emplace_back(name);
  c.def_property(
      name, [member](const Options& o) { return o.*member; },
      [member](Options& o, T value) {
        Options trial = o;
        trial.*member = value;
        validate(trial);
        o = trial;
      },
      doc);
}

}  // namespace

py::dict statistics_dict(const Statistics& s) {
  py::dict d;
  d["steps"] = s.steps;
  d["gradient_evaluations"] = s.gradient_evaluations;
  d["hessian_evaluations"] = s.hessian_evaluations;
  d["hessian_vector_products"] = s.hessian_vector_products;
  d["stage_iterations"] = s.stage_iterations;
  d["newton_fallbacks"] = s.newton_fallbacks;
  d["newton_iterations"] = s.newton_iterations;
  d["state_loads"] = s.state_loads;
  d["processor_applications"] = s.processor_applications;
  d["wall_time"] = s.wall_time;
  d["cpu_time"] = s.cpu_time;
  return d;
}

void bind_options(py::module_& m) {
  py::class_<Options> c(m, "_Options", "erkn::Options (see erkn/integrator.hpp)");
  c.def(py::init<>());
  std::vector<std::string> names;
  field(c, names, "tolerance", &Options::tolerance,
        "stage solver tolerance on theta/(1-theta)|dQ|/|Q|, in [0, 1)");
  field(c, names, "roundoff_level", &Options::roundoff_level,
        "|dQ|/|Q| below which a stalled iteration has reached round-off, in (0, 1)");
  field(c, names, "max_fixed_point_iterations", &Options::max_fixed_point_iterations,
        "fixed-point iterations per stage before Newton, >= 1");
  field(c, names, "max_theta", &Options::max_theta,
        "contraction factor at which fixed point counts as stalled, in (0, 1)");
  field(c, names, "max_newton_iterations", &Options::max_newton_iterations,
        "Newton iterations per stage before the step fails, >= 1");
  field(c, names, "compensated_summation", &Options::compensated_summation,
        "Kahan-compensated update of q and p");
  field(c, names, "pole_tolerance", &Options::pole_tolerance,
        "relative distance to a pole within which h is refused, in (0, 1)");
  field(c, names, "energy_tolerance", &Options::energy_tolerance,
        "energy monitor: a step with |H - H0| > energy_tolerance |H0| fails (0: off)");
  field(c, names, "check_stability", &Options::check_stability,
        "refuse an h the step-size advisor flags at the initial state");
  field(c, names, "blowup_guard", &Options::blowup_guard,
        "stop a run whose energy (or state norm) grows without bound (on by default)");
  c.attr("_fields") = py::tuple(py::cast(names));
}

}  // namespace erkn::python
