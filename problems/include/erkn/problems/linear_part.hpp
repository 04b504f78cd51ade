// M of q'' + Mq = -grad U(q) in its cheapest exact form: scalar, diagonal or symmetric circulant.
// Plain data with its own eigenvalues, so that code independent of the runtime (the experiments'
// peers) can use it; erkn::problems::stiffness() converts it for the runtime.
#pragma once

#include <Eigen/Core>

namespace erkn::problems {

using Vec = Eigen::VectorXd;

struct LinearPart {
  enum class Kind { scalar, diagonal, circulant };
  Kind kind = Kind::scalar;
  double omega2 = 0;  ///< scalar: M = omega2 * I
  Vec diag;           ///< diagonal: M = diag(diag)
  Vec column;         ///< circulant: first column of a symmetric circulant M

  static LinearPart scalar(double w2) { return {Kind::scalar, w2, {}, {}}; }
  static LinearPart diagonal(Vec d) { return {Kind::diagonal, 0, std::move(d), {}}; }
  static LinearPart circulant(Vec c) { return {Kind::circulant, 0, {}, std::move(c)}; }

  /// out = M q (a circulant is applied through its non-zero entries only).
  void apply(const Vec& q, Vec& out) const;
  /// Eigenvalues; for a circulant, lambda_k = sum_j c_j cos(2 pi j k / N), k = 0..N-1.
  Vec eigenvalues(int dim) const;
  /// The dense matrix (tests and small problems only).
  Eigen::MatrixXd dense(int dim) const;
};

}  // namespace erkn::problems
