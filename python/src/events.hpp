// Events from Python: erkn::Event functions that call g(t, q, p) under the GIL, and the hits
// returned as NumPy arrays, one set per event (erkn/events.hpp).
#pragma once

#include <pybind11/pybind11.h>

#include <vector>

#include "erkn/events.hpp"

namespace erkn::python {

namespace py = pybind11;

/// events: a sequence of (g, direction, terminal); g(t, q, p) must return a real number (an
/// erkn.Error names the event otherwise). The functions hold no GIL of their own: call them
/// with the GIL held.
std::vector<Event> events_from_python(const py::sequence& events);

/// (t_events, q_events, p_events, statistics): per event an array of times (n_k,) and the
/// states (n_k, d) there; the work spent locating them.
py::tuple hits_to_python(const Events& events, std::size_t count, Eigen::Index d);

}  // namespace erkn::python
