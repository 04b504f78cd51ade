// The problems library shared by tests, benchmarks and experiments: oscillatory Hamiltonian
// systems q'' + Mq = -grad U(q), H = p'p/2 + q'Mq/2 + U(q), each defined once with its gradient,
// potential, Hessian, a long-double force for reference solutions, and its exact solution where
// known. The paper's test problems (section 4.2, docs/design.md §4) are the defaults.
//
//   const erkn::problems::Problem p = erkn::problems::sine_gordon(32);
//   erkn::Integrator run(erkn::Method::by_name("SERKN2s4"), erkn::problems::system(p), 1.0 / 40,
//                        p.q0, p.p0);
#pragma once

#include <Eigen/Core>
#include <erkn/integrator.hpp>
#include <erkn/system.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "erkn/problems/linear_part.hpp"

namespace erkn::problems {

using VecLD = std::vector<long double>;

/// A quantity the flow conserves: H exactly; an adiabatic invariant (FPU's oscillatory energies)
/// only up to small oscillations, over times long in its parameter (Hairer-Lubich-Wanner XIII).
struct Invariant {
  std::string name;
  std::function<double(const Vec& q, const Vec& p)> value;
  bool exact = true;
};

/// U with its gradient and Hessian for any dimension: the problems' nonlinear parts, and the
/// Python module's built-in potentials (one definition for both).
struct Potential {
  std::function<void(const Vec& q, Vec& grad)> grad_u;
  std::function<double(const Vec& q)> potential;
  std::function<Eigen::MatrixXd(const Vec& q)> hessian_u;
  /// hv = Hess U(q) v in closed form (modified kicks form grad(|grad U|^2) = 2 Hess U grad U).
  std::function<void(const Vec& q, const Vec& v, Vec& hv)> hessian_vector_u;
  /// grad_u's functor compiled into the explicit steppers of d <= 4 with M's identity eigenbasis
  /// and of a half-spectrum basis (erkn/compiled_gradient.hpp), for Integrator's constructor that
  /// takes them: the same arithmetic as grad_u, and in modified kicks as hessian_vector_u,
  /// without a std::function call per stage; nullptr where there is none.
  std::shared_ptr<const detail::CompiledSteppers> compiled_grad_u;
};

/// U = -kappa sum_i cos q_i (sine-Gordon: grad U = kappa sin q).
Potential sine_potential(double kappa = 1);
/// U = -k^2 sum_i (q_i^4 - q_i^2) / 2 (Duffing: q'' + M q = k^2 (2 q^3 - q)).
Potential duffing_potential(double k);
/// U = beta/4 sum_i q_i^4 (phi^4; the quadratic part belongs in M).
Potential quartic_potential(double beta);
/// The FPU chain's U for m stiff springs (see fpu()); d = 2m.
Potential fpu_potential(int m);

struct Problem {
  std::string key;    ///< "P1", "P2", "P3", or a scene's own key
  std::string title;  ///< e.g. "sine-Gordon, N = 32"
  LinearPart M;
  Vec q0, p0;
  double t_error = 10;           ///< error is measured at this time
  double h_energy = 0;           ///< the paper's fixed step for the energy chart
  std::vector<int> paper_steps;  ///< the paper's step counts on [0, t_error] (both sweeps)

  std::function<void(const Vec& q, Vec& grad)> grad_u;
  std::function<double(const Vec& q)> potential;
  std::function<Eigen::MatrixXd(const Vec& q)> hessian_u;
  /// hv = Hess U(q) v in closed form (every problem has one: the grids too), for the modified
  /// force grad(|grad U|^2) = 2 Hess U grad U of modified-kick methods.
  std::function<void(const Vec& q, const Vec& v, Vec& hv)> hessian_vector_u;
  /// Full force -Mq - grad U(q) in long double, for the reference solution.
  std::function<void(const VecLD& q, VecLD& force)> force_ld;
  /// Exact q(t), where known.
  std::optional<std::function<Vec(double t)>> exact;
  /// Invariants beyond H (FPU: the stiff springs' energies I_1..I_m and their sum I).
  std::vector<Invariant> adiabatic;

  int dim() const { return int(q0.size()); }
  double energy(const Vec& q, const Vec& p) const;
  /// force = -Mq - grad U(q).
  void force(const Vec& q, Vec& force) const;
};

/// P1: sine-Gordon on [-1, 1], periodic, N points, dx = 2/N, M = circulant(-1, 2, -1)/dx^2,
/// U = -kappa sum cos u_i (the paper: N = 32, kappa = 1; a large kappa makes the nonlinear part
/// stiff), u(0) = pi, u'(0) = sqrt(N) (0.01 + sin(2 pi i / N)).
Problem sine_gordon(int n, double kappa = 1);
/// P2: Duffing q'' + 100 q = k^2 (2 q^3 - q), q(0) = 0, q'(0) = 10; exact q = sn(10 t, k/10).
Problem duffing(double k = 0.03);
/// P3: stellar orbits q1'' + 4 q1 = eps q2^2, q2'' + q2 = 2 eps q1 q2, q(0) = (1, 1), q'(0) = 0.
Problem stellar_orbits(double eps = 1e-3);
/// 2-D sine-Gordon u_tt = Lap u - sin u, periodic on [-6, 6)^2 with n x n points (row-major,
/// x along the first axis): u0 = 2.5 exp(-(x^2 + y^2)), u_t(0) = 0; U = -sum cos u; error at
/// t = 1. No Hessian (no d x d matrix on a grid).
Problem sine_gordon_2d(int n);
/// FPU: Hairer-Lubich-Wanner's Fermi-Pasta-Ulam chain (GNI section I.5.1) of m stiff springs,
/// q = (x0_1..x0_m, x1_1..x1_m), M = diag(0, omega^2), U = 1/4 sum_i u_i^4 with the elongations
/// u_0 = x0_1 - x1_1, u_i = x0_{i+1} - x1_{i+1} - x0_i - x1_i, u_m = x0_m + x1_m;
/// x0_1 = 1, x0_1' = 1, x1_1 = 1/omega, x1_1' = 1, all else 0. Its numerical resonances at
/// h omega near k pi are what erkn::advise_step_size is tested on. Adiabatic invariants: the
/// stiff springs' energies I_j = (x1_j'^2 + omega^2 x1_j^2) / 2 and I = sum_j I_j (HLW I.5.1).
Problem fpu(int m = 3, double omega = 50);
/// Klein-Gordon / phi^4 u_tt = Lap u - u - u^3 on [0, 1]^dims (dims = 1, 2, 3), Dirichlet, n
/// interior points per axis (row-major, the last axis fastest): u0 = 2 prod_a sin(pi x_a) +
/// exp(-100 |x - c|^2), c = (0.3, 0.4, 0.5) (its first dims entries), u_t(0) = 0;
/// M = -Lap_h + 1 (mass shift), U = sum u^4 / 4. Error at t = 1. No Hessian.
Problem klein_gordon(int n, int dims = 3);
/// Henon-Heiles: H = |p|^2/2 + |q|^2/2 + q1^2 q2 - q2^3/3 (M = I, U = q1^2 q2 - q2^3/3), started
/// at q = (0, 0.1), p = (p1, 0) with p1 > 0 from the energy H0 (below the escape energy 1/6);
/// error at t = 20.
Problem henon_heiles(double energy = 0.13);

/// "P1", "P2", "P3" -> the paper's problem, "FPU" -> fpu(), "HH" -> henon_heiles(); throws
/// std::invalid_argument otherwise.
Problem problem_by_key(const std::string& key);

/// H (exact) and then the problem's adiabatic invariants.
std::vector<Invariant> invariants(const Problem& p);

/// M in the runtime's form (scalar, diagonal, circulant).
Stiffness stiffness(const LinearPart& m);
/// The problem as the runtime's System: M, gradient, potential, Hessian (where the problem has
/// one) and Hessian-vector product.
System system(const Problem& p);
/// M with the potential u: a System for scenes built outside this library (a test's grid, a
/// sweep's wave grid) that reuse one of its potentials.
System system(Stiffness M, const Potential& u);

}  // namespace erkn::problems
