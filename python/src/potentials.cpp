#include "potentials.hpp"

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "erkn/error.hpp"

namespace erkn::python {
namespace {

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

// U = -sum_i cos q_i (sine-Gordon, problem 1 of the paper: the force is -sin q).
System sine() {
  System s;
  s.gradient = [](const Vector& q, Vector& g) { g = q.array().sin(); };
  s.potential = [](const Vector& q) { return -q.array().cos().sum(); };
  s.hessian = [](const Vector& q, Matrix& H) { H = q.array().cos().matrix().asDiagonal(); };
  return s;
}

// U = k^2 sum_i (q_i^2 - q_i^4) / 2 (Duffing, problem 2: q'' + M q = k^2 (2 q^3 - q)).
System duffing(double k) {
  const double k2 = k * k;
  System s;
  s.gradient = [k2](const Vector& q, Vector& g) { g = k2 * (q.array() - 2 * q.array().cube()); };
  s.potential = [k2](const Vector& q) {
    return 0.5 * k2 * (q.array().square() - q.array().square().square()).sum();
  };
  s.hessian = [k2](const Vector& q, Matrix& H) {
    H = (k2 * (1 - 6 * q.array().square())).matrix().asDiagonal();
  };
  return s;
}

// U = beta/4 sum_i q_i^4 (a phi^4 lattice; the quadratic part belongs in M).
System phi4(double beta) {
  System s;
  s.gradient = [beta](const Vector& q, Vector& g) { g = beta * q.array().cube(); };
  s.potential = [beta](const Vector& q) { return 0.25 * beta * q.array().square().square().sum(); };
  s.hessian = [beta](const Vector& q, Matrix& H) {
    H = (3 * beta * q.array().square()).matrix().asDiagonal();
  };
  return s;
}

// Fermi-Pasta-Ulam in the coordinates of Hairer, Lubich & Wanner (GNI, I.5.1): d = 2m,
// q = (x_1..x_m, y_1..y_m) with y the stiff springs' elongations (M = diag(0, omega^2) is the
// caller's), U = 1/4 sum_k u_k^4 over the soft springs
//   u_0 = x_1 - y_1,  u_i = x_{i+1} - y_{i+1} - x_i - y_i (i = 1..m-1),  u_m = x_m + y_m.
// Each u_k = c_k^T q with at most four nonzero c_k entries.
struct Springs {
  Eigen::Index d = 0;
  std::vector<std::vector<std::pair<Eigen::Index, double>>> c;
  const Springs& at(const Vector& q) const {
    if (q.size() != d)
      throw Error("the fpu potential was set up for d = " + std::to_string(d) + ", got q of size " +
                  std::to_string(q.size()));
    return *this;
  }
  double u(std::size_t k, const Vector& q) const {
    double s = 0;
    for (const auto& [i, a] : c[k]) s += a * q[i];
    return s;
  }
};

Springs fpu_springs(Eigen::Index d) {
  if (d % 2 != 0 || d == 0)
    throw Error("the fpu potential needs an even dimension d = 2m; got d = " + std::to_string(d));
  const Eigen::Index m = d / 2;
  Springs s;
  s.d = d;
  s.c.push_back({{0, 1.0}, {m, -1.0}});
  for (Eigen::Index i = 0; i + 1 < m; ++i)
    s.c.push_back({{i + 1, 1.0}, {m + i + 1, -1.0}, {i, -1.0}, {m + i, -1.0}});
  s.c.push_back({{m - 1, 1.0}, {2 * m - 1, 1.0}});
  return s;
}

System fpu(Eigen::Index d) {
  const auto springs = std::make_shared<const Springs>(fpu_springs(d));  // (immutable: shareable)
  System s;
  s.gradient = [springs](const Vector& q, Vector& g) {
    const Springs& sp = springs->at(q);
    g.setZero();
    for (std::size_t k = 0; k < sp.c.size(); ++k) {
      const double u = sp.u(k, q), w = u * u * u;
      for (const auto& [i, a] : sp.c[k]) g[i] += a * w;
    }
  };
  s.potential = [springs](const Vector& q) {
    const Springs& sp = springs->at(q);
    double U = 0;
    for (std::size_t k = 0; k < sp.c.size(); ++k) U += 0.25 * std::pow(sp.u(k, q), 4);
    return U;
  };
  s.hessian = [springs](const Vector& q, Matrix& H) {
    const Springs& sp = springs->at(q);
    H.setZero();
    for (std::size_t k = 0; k < sp.c.size(); ++k) {
      const double w = 3 * std::pow(sp.u(k, q), 2);
      for (const auto& [i, a] : sp.c[k])
        for (const auto& [j, b] : sp.c[k]) H(i, j) += w * a * b;
    }
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

std::map<std::string, std::map<std::string, double>> builtin_potentials() {
  return {{"sine", {}}, {"duffing", {{"k", 0.03}}}, {"fpu", {}}, {"phi4", {{"beta", 1.0}}}};
}

System builtin_potential(const std::string& name, const std::map<std::string, double>& params,
                         Eigen::Index d) {
  const auto all = builtin_potentials();
  const auto it = all.find(name);
  if (it == all.end())
    throw Error("unknown built-in potential '" + name + "'; known: sine, duffing, fpu, phi4");
  if (it->second.empty() && !params.empty())
    throw Error("the " + name + " potential has no parameters");
  if (name == "sine") return sine();
  if (name == "fpu") return fpu(d);
  const double value = parameter(name, params, it->second);
  return name == "duffing" ? duffing(value) : phi4(value);
}

}  // namespace erkn::python
