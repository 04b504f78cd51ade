// A System assembled from Python: M (a Stiffness) with U's gradient, potential and Hessian,
// each either built in (C++) or a Python callable.
#pragma once

#include <pybind11/pybind11.h>

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
  /// The gradient compiled into the explicit steppers of d <= 4 (a built-in potential's,
  /// problems::Potential::compiled_grad_u), or nullptr.
  std::shared_ptr<const detail::CompiledSteppers> compiled = nullptr;
};

}  // namespace erkn::python
