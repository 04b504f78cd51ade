// _erkn: the compiled part of the erkn Python package (python/erkn/__init__.py wraps it).
#include <erkn/error.hpp>

#include "bindings.hpp"

PYBIND11_MODULE(_erkn, m) {
  m.doc() = "erkn runtime: symplectic ERKN integrators for q'' + M q = -grad U(q)";
  // Every erkn::Error arrives as erkn.Error (a ValueError) carrying erkn's message.
  pybind11::register_exception<erkn::Error>(m, "Error", PyExc_ValueError);
  erkn::python::bind_registry(m);
  erkn::python::bind_system(m);
  erkn::python::bind_options(m);
  erkn::python::bind_integrator(m);
  erkn::python::bind_advisor(m);
  erkn::python::bind_ensemble(m);
  erkn::python::bind_problems(m);
}
