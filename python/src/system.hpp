// A System assembled from Python: M (a Stiffness) with U's gradient, potential and Hessian,
// each either built in (C++) or a Python callable.
#pragma once

#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <string>

#include "erkn/integrator.hpp"
#include "erkn/system.hpp"

namespace erkn::python {

struct PySystem {
  System system;
  Eigen::Index d = 0;
  /// Some callback is Python code: the integrator must hold the GIL while it steps.
  bool calls_python = false;
  std::string description;
  /// The gradient and Hessian-vector product compiled into the explicit steppers of d <= 4 and
  /// of a half-spectrum basis (a built-in potential's, problems::Potential::compiled_grad_u), for
  /// every explicit method; or nullptr.
  std::shared_ptr<const detail::CompiledSteppers> compiled = nullptr;
};

/// A built-in potential's System (potentials.hpp) with M: `M` a Python float (M = M I) or an
/// erkn.Stiffness. With `cached`, one of the last 32 asked for when M (a float's bits, a
/// Stiffness's identity: both immutable), name, params and d match: building one costs about a
/// microsecond (four callbacks and the compiled steppers), a third of a short solve's fixed
/// cost; the Integrators built from it copy it.
std::shared_ptr<PySystem> builtin_system(pybind11::handle M, const std::string& name,
                                         const std::map<std::string, double>& params,
                                         Eigen::Index d, bool cached = true);

}  // namespace erkn::python
