// Stiffness factories and System assembly. Python callables are called with read-only NumPy
// views of erkn's vectors (no copy; valid only during the call) and either return the result
// or, with `writes=True`, write it into the writable view passed as the second argument.
#include "system.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "bindings.hpp"
#include "erkn/error.hpp"
#include "erkn/stiffness.hpp"
#include "potentials.hpp"

namespace erkn::python {
namespace {

// A NumPy array viewing x's memory (no copy), read-only unless `writable`.
template <class Matrix>
py::array view(Matrix& x, bool writable) {
  std::vector<py::ssize_t> shape{x.rows()}, strides{py::ssize_t(sizeof(double))};
  if constexpr (Matrix::ColsAtCompileTime != 1) {
    shape.push_back(x.cols());
    strides = {py::ssize_t(sizeof(double)), py::ssize_t(sizeof(double)) * x.rows()};
  }
  py::array a(py::dtype::of<double>(), shape, strides, const_cast<double*>(x.data()), py::none());
  if (!writable)
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// Copies a returned array of the expected shape into out (column-major for a matrix).
template <class Matrix>
void copy_result(const char* what, const py::object& r, Matrix& out) {
  auto a = py::array_t<double, py::array::f_style | py::array::forcecast>::ensure(r);
  const bool vector = Matrix::ColsAtCompileTime == 1;
  if (!a || a.ndim() != (vector ? 1 : 2) || a.shape(0) != out.rows() ||
      (!vector && a.shape(1) != out.cols()))
    throw Error(std::string(what) + " must return a float array of shape (" +
                std::to_string(out.rows()) +
                (vector ? ",)" : ", " + std::to_string(out.cols()) + ")") + "; got " +
                std::string(py::str(r.get_type().attr("__name__"))) +
                (a ? " of shape " + std::string(py::str(py::cast(a.request().shape))) : ""));
  std::copy(a.data(), a.data() + out.size(), out.data());
}

// Calls f(q, out) for a callback that writes into out. out is filled with NaN first: an entry
// left NaN means f rebound `out` (out = q**3) instead of writing into it, or wrote NaN; either
// is refused (one pass over out, against a Python call).
template <class Matrix>
void call_writing(const char* what, const py::object& f, const Eigen::VectorXd& q, Matrix& out) {
  out.setConstant(std::numeric_limits<double>::quiet_NaN());
  f(view(q, false), view(out, true));
  for (Eigen::Index i = 0; i < out.size(); ++i)
    if (std::isnan(out.data()[i]))
      throw Error(std::string(what) + " left entry " + std::to_string(i) +
                  " of out NaN: write into out in place (out[:] = ...), do not rebind it");
}

// U(q) from a Python potential: a float (or anything float() accepts, e.g. a NumPy scalar).
double potential_value(const py::object& potential, const Eigen::VectorXd& q) {
  const py::object r = potential(view(q, false));
  try {
    if (PyNumber_Check(r.ptr())) return py::float_(r).cast<double>();  // (a str is no number)
  } catch (const py::error_already_set&) {  // (float() refused it: an array of size > 1)
  }
  throw Error("potential(q) must return a float; got " +
              std::string(py::str(r.get_type().attr("__name__"))));
}

System python_callbacks(const py::object& grad, bool grad_writes, const py::object& potential,
                        const py::object& hessian, bool hessian_writes,
                        const py::object& hessian_vector_product) {
  System s;
  s.gradient = [grad, grad_writes](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    if (grad_writes) return call_writing("grad(q, out)", grad, q, g);
    copy_result("grad(q)", grad(view(q, false)), g);
  };
  if (!potential.is_none())
    s.potential = [potential](const Eigen::VectorXd& q) { return potential_value(potential, q); };
  if (!hessian.is_none())
    s.hessian = [hessian, hessian_writes](const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
      if (hessian_writes) return call_writing("hessian(q, out)", hessian, q, H);
      copy_result("hessian(q)", hessian(view(q, false)), H);
    };
  if (!hessian_vector_product.is_none())
    s.hessian_vector_product = [f = hessian_vector_product](const Eigen::VectorXd& q,
                                                            const Eigen::VectorXd& v,
                                                            Eigen::VectorXd& hv) {
      hv.resize(q.size());
      copy_result("hessian_vector_product(q, v)", f(view(q, false), view(v, false)), hv);
    };
  return s;
}

// The built-in Systems last asked for (builtin_system), the most recent last.
class BuiltinSystems {
 public:
  std::shared_ptr<PySystem> get(py::handle M, const std::string& name,
                                const std::map<std::string, double>& params, Eigen::Index d) {
    const auto hit = std::find_if(entries_.rbegin(), entries_.rend(), [&](const Entry& e) {
      return e.d == d && same_stiffness(e.M, M) && e.name == name && e.params == params;
    });
    if (hit != entries_.rend()) {
      std::rotate(hit.base() - 1, hit.base(), entries_.end());
      return entries_.back().system;
    }
    auto system = build(M, name, params, d);
    if (entries_.size() == kSize) entries_.erase(entries_.begin());
    entries_.push_back({py::reinterpret_borrow<py::object>(M), name, params, d, system});
    return system;
  }

  static std::shared_ptr<PySystem> build(py::handle M, const std::string& name,
                                         const std::map<std::string, double>& params,
                                         Eigen::Index d) {
    const Stiffness stiffness = PyFloat_CheckExact(M.ptr())
                                    ? Stiffness::scalar(PyFloat_AS_DOUBLE(M.ptr()))
                                    : M.cast<const Stiffness&>();  // (M first, as any grad)
    auto system = std::make_shared<PySystem>(builtin_potential(name, params, d));
    system->system.M = stiffness;
    return system;
  }

 private:
  static constexpr size_t kSize = 32;
  struct Entry {
    py::object M;
    std::string name;
    std::map<std::string, double> params;
    Eigen::Index d;
    std::shared_ptr<PySystem> system;
  };
  // The same float bits (0.0 and -0.0 differ), or the same erkn.Stiffness object.
  static bool same_stiffness(const py::object& a, py::handle b) {
    if (a.ptr() == b.ptr()) return true;
    if (!PyFloat_CheckExact(a.ptr()) || !PyFloat_CheckExact(b.ptr())) return false;
    const double x = PyFloat_AS_DOUBLE(a.ptr()), y = PyFloat_AS_DOUBLE(b.ptr());
    return std::memcmp(&x, &y, sizeof x) == 0;
  }
  std::vector<Entry> entries_;
};

std::string structure_name(Stiffness::Structure s) {
  switch (s) {
    case Stiffness::Structure::scalar:
      return "scalar";
    case Stiffness::Structure::diagonal:
      return "diagonal";
    case Stiffness::Structure::circulant:
      return "circulant";
    case Stiffness::Structure::dense:
      return "dense";
    case Stiffness::Structure::grid:
      return "grid";
  }
  return "?";
}

// Stiffness and its factories (scalar, diagonal, circulant, dense, grid).
void bind_stiffness(py::module_& m) {
  py::class_<Stiffness>(m, "Stiffness", "The matrix M in the cheapest form that is exact.")
      .def_property_readonly("structure",
                             [](const Stiffness& M) { return structure_name(M.structure()); })
      .def_property_readonly("dim", &Stiffness::dim, "d (0 for scalar: fits any dimension)")
      .def_property_readonly("eigenvalues",
                             [](const Stiffness& M) { return Eigen::VectorXd(M.eigenvalues()); })
      .def("to_dense", &Stiffness::to_dense, py::arg("d"))
      .def("__repr__", [](const Stiffness& M) {
        return "erkn.Stiffness(" + structure_name(M.structure()) +
               ", d=" + std::to_string(M.dim()) + ")";
      });
  m.def("scalar", &Stiffness::scalar, py::arg("omega2"), "M = omega2 I");
  m.def(
      "diagonal", [](const Eigen::Ref<const Eigen::VectorXd>& d) { return Stiffness::diagonal(d); },
      py::arg("m"), "M = diag(m)");
  m.def(
      "circulant",
      [](const Eigen::Ref<const Eigen::VectorXd>& c) { return Stiffness::circulant(c); },
      py::arg("col"), "circulant M from its first column (symmetric: col[j] = col[N-j])");
  m.def(
      "dense", [](const Eigen::Ref<const Eigen::MatrixXd>& a) { return Stiffness::dense(a); },
      py::arg("m"), "dense symmetric positive semi-definite M");
  m.def(
      "grid",
      [](const std::vector<std::tuple<Eigen::Index, double, std::string>>& axes, double shift) {
        std::vector<GridAxis> a;
        for (const auto& [n, spacing, b] : axes)
          a.push_back({n, spacing, GridAxis::boundary_named(b)});
        return Stiffness::grid(std::move(a), shift);
      },
      py::arg("axes"), py::arg("shift") = 0.0,
      "M = shift I - sum_a D2_a on a tensor grid; axes: [(n, spacing, 'periodic'|'dirichlet'|"
      "'neumann'), ...], unknowns in C order");
}

// System: its dimension, description and callbacks, callable from Python.
void bind_system_class(py::module_& m) {
  py::class_<PySystem, std::shared_ptr<PySystem>>(m, "System")
      .def_readonly("dim", &PySystem::d)
      .def_readonly("description", &PySystem::description)
      .def_property_readonly("has_potential",
                             [](const PySystem& s) { return bool(s.system.potential); })
      .def(
          "gradient",
          [](const PySystem& s, const Eigen::VectorXd& q) {
            Eigen::VectorXd g(q.size());
            s.system.gradient(q, g);
            return g;
          },
          py::arg("q"), "grad U(q)")
      .def(
          "potential",
          [](const PySystem& s, const Eigen::VectorXd& q) {
            if (!s.system.potential) throw Error("this system has no potential");
            return s.system.potential(q);
          },
          py::arg("q"), "U(q)")
      .def(
          "hessian",
          [](const PySystem& s, const Eigen::VectorXd& q) {
            if (!s.system.hessian) throw Error("this system has no Hessian");
            Eigen::MatrixXd H(q.size(), q.size());
            s.system.hessian(q, H);
            return H;
          },
          py::arg("q"), "the Hessian of U at q")
      .def(
          "hessian_vector_product",
          [](const PySystem& s, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
            if (!s.system.hessian_vector_product)
              throw Error("this system has no Hessian-vector product");
            if (v.size() != q.size()) throw Error("q and v must have the same size");
            Eigen::VectorXd hv(q.size());
            s.system.hessian_vector_product(q, v, hv);
            return hv;
          },
          py::arg("q"), py::arg("v"),
          "Hess U(q) v (modified kicks form grad(|grad U|^2) = 2 Hess U grad U from it)");
}

// The Systems erkn.solve builds: a built-in potential or Python callbacks.
void bind_system_factories(py::module_& m) {
  m.def("_builtin_system", &builtin_system, py::arg("M"), py::arg("name"), py::arg("params"),
        py::arg("d"), py::arg("cached"));
  m.def(
      "_python_system",
      [](const Stiffness& M, const py::object& grad, bool grad_writes, const py::object& potential,
         const py::object& hessian, bool hessian_writes, const py::object& hessian_vector_product,
         Eigen::Index d) {
        PySystem s{python_callbacks(grad, grad_writes, potential, hessian, hessian_writes,
                                    hessian_vector_product),
                   d, true, "Python callbacks"};
        s.system.M = M;
        return s;
      },
      py::arg("M"), py::arg("grad"), py::arg("grad_writes"), py::arg("potential"),
      py::arg("hessian"), py::arg("hessian_writes"), py::arg("hessian_vector_product"),
      py::arg("d"));
  m.def("builtin_potentials", &builtin_potentials,
        "the built-in potentials: {name: {parameter: default}}");
}

}  // namespace

std::shared_ptr<PySystem> builtin_system(py::handle M, const std::string& name,
                                         const std::map<std::string, double>& params,
                                         Eigen::Index d, bool cached) {
  // (Never destroyed: it holds Python objects, which must not be released after the interpreter
  // has ended.)
  static auto* const recent = new BuiltinSystems;
  return cached ? recent->get(M, name, params, d) : BuiltinSystems::build(M, name, params, d);
}

void bind_system(py::module_& m) {
  bind_stiffness(m);
  bind_system_class(m);
  bind_system_factories(m);
}

}  // namespace erkn::python
