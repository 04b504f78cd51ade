// Built-in potentials U, evaluated in C++ so small systems do not pay a Python call per
// gradient: the problems library's definitions (erkn/problems.hpp), by name.
#pragma once

#include <map>
#include <string>

#include "system.hpp"

namespace erkn::python {

/// A System's U with its gradient (also compiled into the small explicit steppers where the
/// problems library has it so), Hessian and Hessian-vector product (closed forms) for dimension
/// d (M is set by the caller).
PySystem builtin_potential(const std::string& name, const std::map<std::string, double>& params,
                           Eigen::Index d);

/// The names, each with its parameters and their defaults, for messages and documentation.
const std::map<std::string, std::map<std::string, double>>& builtin_potentials();

}  // namespace erkn::python
