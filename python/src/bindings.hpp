// The pieces of the _erkn extension module, one function per group of bindings.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>

#include "erkn/integrator.hpp"

namespace erkn::python {

namespace py = pybind11;

/// A 1-D float array argument: a contiguous float64 array is read in place, anything else is
/// converted. (pybind11's caster for `const Eigen::VectorXd&` copies through a NumPy array
/// made for the copy, ~5k instructions per argument: a third of a constructor's cost.)
using VectorArg = Eigen::Ref<const Eigen::VectorXd>;

/// erkn.methods(), erkn.tableau(name, v), erkn.stability(name, V, z).
void bind_registry(py::module_& m);
/// Stiffness and its factories; System (M with gradient, potential and Hessian, built in or
/// Python callables); the built-in potentials.
void bind_system(py::module_& m);
/// Integrator: step, integrate with output, state_at, statistics.
void bind_integrator(py::module_& m);
/// Options (every erkn::Options field, validated on assignment by erkn::validate).
void bind_options(py::module_& m);
/// advise_step_size with its report, hessian_bounds_at and hessian_bounds_along; _choose
/// (choose_method_and_step).
void bind_advisor(py::module_& m);
/// The problems library (problems/): _Problem and its constructors, for erkn.problems.
void bind_problems(py::module_& m);
/// Ensemble: trajectories on threads, without the GIL for built-in potentials.
void bind_ensemble(py::module_& m);

/// erkn::Statistics as the dict Integrator.statistics and Ensemble results carry.
py::dict statistics_dict(const Statistics& s);

}  // namespace erkn::python
