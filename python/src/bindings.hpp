// The pieces of the _erkn extension module, one function per group of bindings.
#pragma once

#include <pybind11/pybind11.h>

namespace erkn::python {

namespace py = pybind11;

/// erkn.methods(), erkn.tableau(name, v), erkn.stability(name, V, z).
void bind_registry(py::module_& m);
/// Stiffness and its factories; System (M with gradient, potential and Hessian, built in or
/// Python callables); the built-in potentials.
void bind_system(py::module_& m);
/// Integrator: step, integrate with output, state_at, statistics.
void bind_integrator(py::module_& m);

}  // namespace erkn::python
