// erkn::Stiffness: the matrix M of q'' + M q = -grad U(q), in the cheapest form that is exact.
//
// The ERKN coefficients are scalar functions of v = h^2 lambda for the eigenvalues lambda of M,
// applied diagonally in M's eigenbasis. Each form below knows its eigenbasis:
//   scalar(w2)         M = w2 I            eigenbasis = identity, one eigenvalue
//   diagonal(m)        M = diag(m)         eigenbasis = identity
//   circulant(col)     M_ik = col[(i-k) mod N], symmetric     eigenbasis = real FFT, eigenvalues in
//                      closed form  lambda_k = sum_j col[j] cos(2 pi j k / N), k = 0..N/2
//   dense(m)           M symmetric PSD     eigendecomposition once, here
// The factories validate (finite; symmetric; positive semi-definite) and throw erkn::Error
// saying how far off the input is. A Stiffness is immutable and cheap to copy (shared data).
#pragma once

#include <Eigen/Core>
#include <memory>

namespace erkn {

class Stiffness {
 public:
  enum class Structure { scalar, diagonal, circulant, dense };

  /// M = omega2 * I in any dimension; omega2 >= 0.
  static Stiffness scalar(double omega2);
  /// M = diag(m), m >= 0.
  static Stiffness diagonal(const Eigen::VectorXd& m);
  /// Circulant M given by its first column; must satisfy col[j] = col[N-j] (symmetry).
  static Stiffness circulant(const Eigen::VectorXd& first_column);
  /// Dense symmetric positive semi-definite M (decomposed once: O(d^3)).
  static Stiffness dense(const Eigen::MatrixXd& m);

  Structure structure() const;
  /// Dimension d of M; 0 for scalar (it fits any dimension).
  Eigen::Index dim() const;
  /// The eigenvalues the coefficients are evaluated at, one per coordinate of the eigenbasis:
  /// scalar: {omega2}; diagonal: m; circulant: lambda_0..lambda_{N/2}; dense: ascending.
  /// Round-off negatives within the PSD tolerance are set to 0.
  const Eigen::VectorXd& eigenvalues() const;
  /// Dense only: orthonormal eigenvectors (columns), in the order of eigenvalues().
  const Eigen::MatrixXd& eigenvectors() const;
  /// Diagonal: m; circulant: the first column; scalar: {omega2}; dense: empty.
  const Eigen::VectorXd& entries() const;
  /// Dense only: M itself.
  const Eigen::MatrixXd& matrix() const;
  /// Circulant only: indices j with first_column[j] != 0 (a stencil when few).
  const Eigen::VectorXi& nonzeros() const;
  /// Dense copy of M in dimension d (for tests and the Newton fallback; O(d^2) memory).
  Eigen::MatrixXd to_dense(Eigen::Index d) const;

  /// Relative tolerance of the symmetry and PSD checks (times the largest |entry| or |lambda|).
  static constexpr double kTolerance = 1e-12;

  struct Data;

 private:
  explicit Stiffness(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  std::shared_ptr<const Data> data_;
};

}  // namespace erkn
