// erkn.Ensemble: erkn::Ensemble over Systems from Python. The trajectories run on worker threads
// with the GIL released; a System whose callbacks are Python code is wrapped so that each call
// takes the GIL (those trajectories then take turns in Python, the rest runs in parallel).
#include "erkn/ensemble.hpp"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>
#include <vector>

#include "bindings.hpp"
#include "erkn/error.hpp"
#include "system.hpp"

namespace erkn::python {
namespace {

// Calls f holding the GIL; a Python exception becomes an erkn::Error before the GIL is let go
// (its state must not be released by a worker thread without it).
template <class F>
auto with_gil(const char* what, F&& f) {
  py::gil_scoped_acquire gil;
  try {
    return f();
  } catch (py::error_already_set& e) {
    throw Error(std::string(what) + " raised " + e.what());
  }
}

// Python callbacks behind a shared pointer: copying the System on a worker thread copies the
// pointer, never a Python reference (which would need the GIL).
System thread_safe(const PySystem& s) {
  if (!s.calls_python) return s.system;
  const auto shared = std::make_shared<const System>(s.system);
  System out;
  out.M = s.system.M;
  out.gradient = [shared](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    with_gil("grad", [&] { shared->gradient(q, g); });
  };
  if (shared->potential)
    out.potential = [shared](const Eigen::VectorXd& q) {
      return with_gil("potential", [&] { return shared->potential(q); });
    };
  if (shared->hessian)
    out.hessian = [shared](const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
      with_gil("hessian", [&] { shared->hessian(q, H); });
    };
  if (shared->hessian_vector_product)
    out.hessian_vector_product = [shared](const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                          Eigen::VectorXd& hv) {
      with_gil("hessian_vector_product", [&] { shared->hessian_vector_product(q, v, hv); });
    };
  return out;
}

py::dict result(const TrajectoryResult& r) {
  py::dict d;
  d["q"] = r.q;
  d["p"] = r.p;
  d["t"] = r.t;
  d["error"] = r.error;
  d["statistics"] = statistics_dict(r.statistics);
  return d;
}

// One Ensemble; members i = 0..n-1 take systems[i] (or systems[0] for all) and row i of q0, p0.
Ensemble make(const std::string& method, double h, const std::vector<const PySystem*>& systems,
              const Eigen::MatrixXd& q0, const Eigen::MatrixXd& p0, const Options& options) {
  if (q0.rows() != p0.rows() || q0.cols() != p0.cols())
    throw Error("Ensemble: q0 and p0 must have the same shape (n, d)");
  if (systems.size() != 1 && Eigen::Index(systems.size()) != q0.rows())
    throw Error("Ensemble: " + std::to_string(systems.size()) + " systems for " +
                std::to_string(q0.rows()) + " trajectories (give one, or one per trajectory)");
  std::vector<Member> members;
  for (Eigen::Index i = 0; i < q0.rows(); ++i)
    members.push_back({thread_safe(*systems[systems.size() == 1 ? 0 : i]), q0.row(i).transpose(),
                       p0.row(i).transpose()});
  return Ensemble(Method::by_name(method), h, std::move(members), options);
}

}  // namespace

void bind_ensemble(py::module_& m) {
  py::class_<Ensemble>(m, "_Ensemble")
      .def(py::init(&make), py::arg("method"), py::arg("h"), py::arg("systems"), py::arg("q0"),
           py::arg("p0"), py::arg("options"))
      .def_property_readonly("size", &Ensemble::size)
      .def(
          "_integrate",
          [](const Ensemble& e, double t_end, int threads) {
            std::vector<TrajectoryResult> r;
            {
              py::gil_scoped_release release;
              r = e.integrate(t_end, threads);
            }
            py::list out;
            for (const TrajectoryResult& x : r) out.append(result(x));
            return out;
          },
          py::arg("t_end"), py::arg("threads"));
}

}  // namespace erkn::python
