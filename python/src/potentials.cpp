#include "potentials.hpp"

#include <cmath>
#include <utility>

#include "erkn/error.hpp"
#include "erkn/problems.hpp"

namespace erkn::python {
namespace {

using Vector = Eigen::VectorXd;

// The problems library's U (problems/src/potentials.cpp, fpu.cpp: one definition for C++ and
// Python) as a System's U.
System from(problems::Potential u) {
  System s;
  s.gradient = std::move(u.grad_u);
  s.potential = std::move(u.potential);
  s.hessian = [h = std::move(u.hessian_u)](const Vector& q, Eigen::MatrixXd& H) { H = h(q); };
  s.hessian_vector_product = std::move(u.hessian_vector_u);
  return s;
}

// A built-in potential's PySystem for dimension d: u's System and its compiled gradient.
PySystem builtin(const std::string& name, problems::Potential u, Eigen::Index d) {
  auto compiled = std::move(u.compiled_grad_u);
  return {from(std::move(u)), d, false, "built-in " + name, std::move(compiled)};
}

// Fermi-Pasta-Ulam in the coordinates of Hairer, Lubich & Wanner (GNI, I.5.1): d = 2m,
// q = (x_1..x_m, y_1..y_m), y the stiff springs' elongations (M = diag(0, omega^2) is the
// caller's). Its U reads q[0..d-1]: a q of another size is refused.
System fpu(Eigen::Index d) {
  if (d % 2 != 0 || d == 0)
    throw Error("the fpu potential needs an even dimension d = 2m; got d = " + std::to_string(d));
  System s = from(problems::fpu_potential(int(d / 2)));
  const auto check = [d](const Vector& q) {
    if (q.size() != d)
      throw Error("the fpu potential was set up for d = " + std::to_string(d) + ", got q of size " +
                  std::to_string(q.size()));
  };
  s.gradient = [g = s.gradient, check](const Vector& q, Vector& out) { check(q), g(q, out); };
  s.potential = [u = s.potential, check](const Vector& q) { return check(q), u(q); };
  s.hessian = [h = s.hessian, check](const Vector& q, Eigen::MatrixXd& H) { check(q), h(q, H); };
  s.hessian_vector_product = [hv = s.hessian_vector_product, check](const Vector& q,
                                                                    const Vector& v, Vector& out) {
    check(q), hv(q, v, out);
  };
  return s;
}

double parameter(const std::string& name, const std::map<std::string, double>& given,
                 const std::map<std::string, double>& defaults) {
  for (const auto& [key, value] : given)
    if (!defaults.count(key))
      throw Error("the " + name + " potential has no parameter '" + key + "'");
  const std::string key = defaults.begin()->first;
  const auto it = given.find(key);
  const double value = it == given.end() ? defaults.begin()->second : it->second;
  if (!std::isfinite(value)) throw Error(name + ": parameter " + key + " is not finite");
  return value;
}

}  // namespace

const std::map<std::string, std::map<std::string, double>>& builtin_potentials() {
  static const std::map<std::string, std::map<std::string, double>> all{
      {"sine", {}}, {"duffing", {{"k", 0.03}}}, {"fpu", {}}, {"phi4", {{"beta", 1.0}}}};
  return all;
}

PySystem builtin_potential(const std::string& name, const std::map<std::string, double>& params,
                           Eigen::Index d) {
  const auto& all = builtin_potentials();
  const auto it = all.find(name);
  if (it == all.end())
    throw Error("unknown built-in potential '" + name + "'; known: sine, duffing, fpu, phi4");
  if (it->second.empty() && !params.empty())
    throw Error("the " + name + " potential has no parameters");
  if (name == "sine") return builtin(name, problems::sine_potential(), d);
  if (name == "fpu") return {fpu(d), d, false, "built-in fpu"};
  const double value = parameter(name, params, it->second);
  return builtin(
      name,
      name == "duffing" ? problems::duffing_potential(value) : problems::quartic_potential(value),
      d);
}

}  // namespace erkn::python
