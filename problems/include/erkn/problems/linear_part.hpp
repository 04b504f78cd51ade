// M of q'' + Mq = -grad U(q) in its cheapest exact form: scalar, diagonal, symmetric circulant,
// or the shifted Laplacian of a tensor grid. Plain data with its own eigenvalues, so that code
// independent of the runtime (the experiments' peers) can use it; erkn::problems::stiffness()
// converts it for the runtime.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace erkn::problems {

using Vec = Eigen::VectorXd;

/// One axis of a grid: n unknowns `spacing` apart, the second difference closed at both ends by
/// x_{-1} = x_{n-1}, x_n = x_0 (periodic), x_{-1} = x_n = 0 (dirichlet) or x_{-1} = x_0,
/// x_n = x_{n-1} (neumann, cell-centred).
struct GridAxis {
  enum class Boundary { periodic, dirichlet, neumann };
  int n = 0;
  double spacing = 1;
  Boundary boundary = Boundary::periodic;
  /// Eigenvalues of minus the second difference in the order of the axis's real transform
  /// (FFTW R2HC halfcomplex / RODFT00 / REDFT10): 4/spacing^2 sin^2(angle_k).
  Vec eigenvalues() const;
};

struct LinearPart {
  enum class Kind { scalar, diagonal, circulant, grid };
  Kind kind = Kind::scalar;
  double omega2 = 0;           ///< scalar: M = omega2 * I
  Vec diag;                    ///< diagonal: M = diag(diag)
  Vec column;                  ///< circulant: first column of a symmetric circulant M
  std::vector<GridAxis> axes;  ///< grid: M = shift I - sum_a D2_a, row-major, last axis fastest
  double shift = 0;

  static LinearPart scalar(double w2) { return {Kind::scalar, w2, {}, {}, {}, 0}; }
  static LinearPart diagonal(Vec d) { return {Kind::diagonal, 0, std::move(d), {}, {}, 0}; }
  static LinearPart circulant(Vec c) { return {Kind::circulant, 0, {}, std::move(c), {}, 0}; }
  static LinearPart grid(std::vector<GridAxis> a, double s) {
    return {Kind::grid, 0, {}, {}, std::move(a), s};
  }

  /// out = M q (a circulant is applied through its non-zero entries only).
  void apply(const Vec& q, Vec& out) const;
  /// Eigenvalues; for a circulant, lambda_k = sum_j c_j cos(2 pi j k / N), k = 0..N-1; for a
  /// grid, shift + sum_a mu_a[k_a] row-major in the axes' transform orders.
  Vec eigenvalues(int dim) const;
  /// The dense matrix (tests and small problems only).
  Eigen::MatrixXd dense(int dim) const;
};

}  // namespace erkn::problems
