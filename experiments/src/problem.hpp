// The test problems of the paper's section 4.2: q'' + Mq = -grad U(q), H = p'p/2 + q'Mq/2 + U(q).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "linear_part.hpp"

namespace ex {

using VecLD = std::vector<long double>;

struct Problem {
  std::string key;    ///< "P1", "P2", "P3"
  std::string title;  ///< e.g. "sine-Gordon, N = 32"
  LinearPart M;
  Vec q0, p0;
  double t_error = 10;           ///< error is measured at this time
  double h_energy = 0;           ///< the paper's fixed step for the energy chart
  std::vector<int> paper_steps;  ///< the paper's step counts on [0, t_error] (both sweeps)

  std::function<void(const Vec& q, Vec& grad)> grad_u;
  std::function<double(const Vec& q)> potential;
  std::function<Eigen::MatrixXd(const Vec& q)> hessian_u;
  /// Full force -Mq - grad U(q) in long double, for the reference solution.
  std::function<void(const VecLD& q, VecLD& force)> force_ld;
  /// Exact q(t), where known.
  std::optional<std::function<Vec(double t)>> exact;

  int dim() const { return int(q0.size()); }
  double energy(const Vec& q, const Vec& p) const;
  /// force = -Mq - grad U(q).
  void force(const Vec& q, Vec& force) const;
};

Problem sine_gordon(int n);  ///< P1 (paper: n = 32)
Problem duffing();           ///< P2, k = 0.03
Problem stellar_orbits();    ///< P3, epsilon = 1e-3

/// "P1", "P2", "P3" -> problem (P1 with N = 32); throws std::invalid_argument otherwise.
Problem problem_by_key(const std::string& key);

}  // namespace ex
