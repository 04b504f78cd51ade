// A System assembled from Python: M (a Stiffness) with U's gradient, potential and Hessian,
// each either built in (C++) or a Python callable.
#pragma once

#include <pybind11/pybind11.h>

#include "erkn/system.hpp"

namespace erkn::python {

struct PySystem {
  System system;
  Eigen::Index d = 0;
  /// Some callback is Python code: the integrator must hold the GIL while it steps.
  bool calls_python = false;
  std::string description;
};

}  // namespace erkn::python
