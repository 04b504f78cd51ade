#include "events.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>

#include <string>

#include "bindings.hpp"
#include "erkn/error.hpp"

namespace erkn::python {
namespace {

// g(t, q, p) as a double: copies of q and p (the event's state may be kept by g).
double call_event(const py::object& g, std::size_t k, double t, const Eigen::VectorXd& q,
                  const Eigen::VectorXd& p) {
  const py::object r = g(t, q, p);
  if (PyNumber_Check(r.ptr()) && !PyBool_Check(r.ptr())) {
    try {
      return py::float_(r).cast<double>();
    } catch (const py::error_already_set&) {  // (float() refused it: an array of size > 1)
    }
  }
  throw Error("event " + std::to_string(k) + ": g(t, q, p) must return a real number; got " +
              std::string(py::str(r.get_type().attr("__name__"))));
}

}  // namespace

std::vector<Event> events_from_python(const py::sequence& events) {
  std::vector<Event> out;
  for (std::size_t k = 0; k < events.size(); ++k) {
    const auto e = events[k].cast<py::tuple>();
    const py::object g = e[0];
    out.push_back({[g, k](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
                     return call_event(g, k, t, q, p);
                   },
                   e[1].cast<int>(), e[2].cast<bool>()});
  }
  return out;
}

py::tuple hits_to_python(const Events& events, std::size_t count, Eigen::Index d) {
  py::list t_events, q_events, p_events;
  for (std::size_t k = 0; k < count; ++k) {
    std::vector<const EventHit*> mine;
    for (const EventHit& h : events.hits())
      if (h.event == k) mine.push_back(&h);
    const auto n = py::ssize_t(mine.size());
    py::array_t<double> t(n), q({n, py::ssize_t(d)}), p({n, py::ssize_t(d)});
    for (py::ssize_t i = 0; i < n; ++i) {
      t.mutable_at(i) = mine[i]->t;
      for (Eigen::Index j = 0; j < d; ++j)
        q.mutable_at(i, j) = mine[i]->q[j], p.mutable_at(i, j) = mine[i]->p[j];
    }
    t_events.append(t), q_events.append(q), p_events.append(p);
  }
  return py::make_tuple(t_events, q_events, p_events, statistics_dict(events.statistics()));
}

}  // namespace erkn::python
