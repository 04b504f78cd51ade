#include "erkn/problems.hpp"

#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace erkn::problems {
namespace {

/// Shortest decimal form of a parameter for titles ("0.03", "1e-03" -> "0.001", "1000").
std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

double Problem::energy(const Vec& q, const Vec& p) const {
  Vec mq;
  M.apply(q, mq);
  return 0.5 * p.squaredNorm() + 0.5 * q.dot(mq) + potential(q);
}

void Problem::force(const Vec& q, Vec& f) const {
  Vec g(q.size());
  grad_u(q, g);
  M.apply(q, f);
  f = -f - g;
}

Problem sine_gordon(int n, double kappa) {
  const double dx = 2.0 / n;
  Problem p;
  p.key = "P1";
  p.title = "sine-Gordon, N = " + std::to_string(n);
  if (kappa != 1) p.title += ", kappa = " + format_number(kappa);
  Vec col = Vec::Zero(n);
  col[0] = 2 / (dx * dx);
  col[1] = col[n - 1] = -1 / (dx * dx);
  p.M = LinearPart::circulant(col);
  p.q0 = Vec::Constant(n, std::numbers::pi);
  p.p0.resize(n);
  for (int i = 1; i <= n; ++i)
    p.p0[i - 1] = std::sqrt(double(n)) * (0.01 + std::sin(2 * std::numbers::pi * i / n));
  p.h_energy = 1.0 / 40;
  p.paper_steps = {400, 800, 1600, 3200, 2000, 4000, 8000, 16000};
  const Potential u = sine_potential(kappa);
  p.grad_u = u.grad_u, p.potential = u.potential, p.hessian_u = u.hessian_u;
  p.hessian_vector_u = u.hessian_vector_u;
  p.force_ld = [n, dx, kappa](const VecLD& q, VecLD& f) {
    const long double s = 1.0L / ((long double)dx * dx);
    for (int i = 0; i < n; ++i) {
      const long double lap = q[(i + n - 1) % n] - 2 * q[i] + q[(i + 1) % n];
      f[i] = s * lap - (long double)kappa * std::sin(q[i]);
    }
  };
  return p;
}

Problem duffing(double k) {
  const double k2 = k * k;
  Problem p;
  p.key = "P2";
  p.title = "Duffing, k = " + format_number(k);
  p.M = LinearPart::scalar(100);
  p.q0 = Vec::Zero(1);
  p.p0 = Vec::Constant(1, 10);
  p.h_energy = 1.0 / 50;
  p.paper_steps = {2000, 4000, 6000, 8000, 400, 800, 1200, 1600};
  const Potential u = duffing_potential(k);
  p.grad_u = u.grad_u, p.potential = u.potential, p.hessian_u = u.hessian_u;
  p.hessian_vector_u = u.hessian_vector_u;
  p.force_ld = [k2](const VecLD& q, VecLD& f) {
    f[0] = -100 * q[0] + (long double)k2 * (2 * q[0] * q[0] * q[0] - q[0]);
  };
  p.exact = [k](double t) { return Vec::Constant(1, boost::math::jacobi_sn(k / 10, 10 * t)); };
  return p;
}

Problem stellar_orbits(double eps) {
  Problem p;
  p.key = "P3";
  p.title = "stellar orbits, epsilon = " + format_number(eps);
  p.M = LinearPart::diagonal(Eigen::Vector2d(4, 1));
  p.q0 = Eigen::Vector2d(1, 1);
  p.p0 = Eigen::Vector2d(0, 0);
  p.h_energy = 1.0 / 10;
  p.paper_steps = {80, 160, 240, 320, 400, 800, 1200, 1600};
  // U(q) = -eps q1 q2^2.
  p.grad_u = [eps](const Vec& q, Vec& g) {
    g.resize(2);
    g[0] = -eps * q[1] * q[1];
    g[1] = -2 * eps * q[0] * q[1];
  };
  p.potential = [eps](const Vec& q) { return -eps * q[0] * q[1] * q[1]; };
  p.hessian_u = [eps](const Vec& q) {
    Eigen::MatrixXd h(2, 2);
    h << 0, -2 * eps * q[1], -2 * eps * q[1], -2 * eps * q[0];
    return h;
  };
  p.hessian_vector_u = [eps](const Vec& q, const Vec& v, Vec& hv) {
    hv.resize(2);
    hv[0] = -2 * eps * q[1] * v[1];
    hv[1] = -2 * eps * (q[1] * v[0] + q[0] * v[1]);
  };
  p.force_ld = [eps](const VecLD& q, VecLD& f) {
    const long double e = eps;
    f[0] = -4 * q[0] + e * q[1] * q[1];
    f[1] = -q[1] + 2 * e * q[0] * q[1];
  };
  return p;
}

Problem sine_gordon_2d(int n) {
  const double L = 12, dx = L / n;
  Problem p;
  p.key = "SG2D";
  p.title = "2-D sine-Gordon, periodic, " + std::to_string(n) + "^2";
  p.M = LinearPart::grid(
      {{n, dx, GridAxis::Boundary::periodic}, {n, dx, GridAxis::Boundary::periodic}}, 0.0);
  p.q0.resize(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -L / 2 + i * dx, y = -L / 2 + j * dx;
      p.q0[i * n + j] = 2.5 * std::exp(-(x * x + y * y));
    }
  p.p0 = Vec::Zero(n * n);
  p.t_error = 1;
  p.grad_u = [](const Vec& q, Vec& g) { g = q.array().sin(); };
  p.potential = [](const Vec& q) { return -q.array().cos().sum(); };
  p.hessian_vector_u = [](const Vec& q, const Vec& v, Vec& hv) {
    hv = q.array().cos() * v.array();
  };
  return p;
}

std::vector<Invariant> invariants(const Problem& p) {
  std::vector<Invariant> out{{"H", [p](const Vec& q, const Vec& v) { return p.energy(q, v); }}};
  out.insert(out.end(), p.adiabatic.begin(), p.adiabatic.end());
  return out;
}

Problem problem_by_key(const std::string& key) {
  if (key == "P1") return sine_gordon(32);
  if (key == "P2") return duffing();
  if (key == "P3") return stellar_orbits();
  if (key == "FPU") return fpu();
  if (key == "HH") return henon_heiles();
  throw std::invalid_argument("unknown problem '" + key + "' (known: P1, P2, P3, FPU, HH)");
}

Problem henon_heiles(double energy) {
  if (!(energy > 0.005 && energy < 1.0 / 6))
    throw std::invalid_argument("Henon-Heiles energy must lie in (0.005, 1/6), got " +
                                format_number(energy));
  Problem p;
  p.key = "HH";
  p.title = "Henon-Heiles, H0 = " + format_number(energy);
  p.M = LinearPart::scalar(1);
  const double y0 = 0.1, v0 = y0 * y0 / 2 - y0 * y0 * y0 / 3;  // the energy at q = (0, y0)
  p.q0 = Eigen::Vector2d(0, y0);
  p.p0 = Eigen::Vector2d(std::sqrt(2 * (energy - v0)), 0);
  p.t_error = 20;
  p.h_energy = 0.1;
  p.grad_u = [](const Vec& q, Vec& g) {
    g.resize(2);
    g[0] = 2 * q[0] * q[1];
    g[1] = q[0] * q[0] - q[1] * q[1];
  };
  p.potential = [](const Vec& q) { return q[0] * q[0] * q[1] - q[1] * q[1] * q[1] / 3; };
  p.hessian_u = [](const Vec& q) {
    Eigen::MatrixXd h(2, 2);
    h << 2 * q[1], 2 * q[0], 2 * q[0], -2 * q[1];
    return h;
  };
  p.hessian_vector_u = [](const Vec& q, const Vec& v, Vec& hv) {
    hv.resize(2);
    hv[0] = 2 * (q[1] * v[0] + q[0] * v[1]);
    hv[1] = 2 * (q[0] * v[0] - q[1] * v[1]);
  };
  p.force_ld = [](const VecLD& q, VecLD& f) {
    f[0] = -q[0] - 2 * q[0] * q[1];
    f[1] = -q[1] - q[0] * q[0] + q[1] * q[1];
  };
  return p;
}

}  // namespace erkn::problems

namespace erkn::problems {

namespace {

erkn::GridAxis::Boundary boundary(GridAxis::Boundary b) {
  switch (b) {
    case GridAxis::Boundary::periodic:
      return erkn::GridAxis::Boundary::periodic;
    case GridAxis::Boundary::dirichlet:
      return erkn::GridAxis::Boundary::dirichlet;
    case GridAxis::Boundary::neumann:
      return erkn::GridAxis::Boundary::neumann;
  }
  throw std::logic_error("unknown grid boundary");
}

}  // namespace

Stiffness stiffness(const LinearPart& m) {
  switch (m.kind) {
    case LinearPart::Kind::scalar:
      return Stiffness::scalar(m.omega2);
    case LinearPart::Kind::diagonal:
      return Stiffness::diagonal(m.diag);
    case LinearPart::Kind::circulant:
      return Stiffness::circulant(m.column);
    case LinearPart::Kind::grid: {
      std::vector<erkn::GridAxis> axes;
      for (const GridAxis& a : m.axes) axes.push_back({a.n, a.spacing, boundary(a.boundary)});
      return Stiffness::grid(axes, m.shift);
    }
  }
  throw std::logic_error("unknown LinearPart kind");
}

System system(const Problem& p) {
  return system(stiffness(p.M), {p.grad_u, p.potential, p.hessian_u, p.hessian_vector_u, nullptr});
}

System system(Stiffness M, const Potential& u) {
  System s;
  s.M = std::move(M);
  s.gradient = u.grad_u;
  s.potential = u.potential;
  if (u.hessian_u)  // (the grid problems have none: no d x d matrix there)
    s.hessian = [h = u.hessian_u](const Vec& q, Eigen::MatrixXd& hess) { hess = h(q); };
  s.hessian_vector_product = u.hessian_vector_u;
  return s;
}

}  // namespace erkn::problems
