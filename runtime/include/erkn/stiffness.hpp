// erkn::Stiffness: the matrix M of q'' + M q = -grad U(q), in the cheapest form that is exact.
//
// The ERKN coefficients are scalar functions of v = h^2 lambda for the eigenvalues lambda of M,
// applied diagonally in M's eigenbasis. Each form below knows its eigenbasis:
//   scalar(w2)         M = w2 I            eigenbasis = identity, one eigenvalue
//   diagonal(m)        M = diag(m)         eigenbasis = identity
//   circulant(col)     M_ik = col[(i-k) mod N], symmetric     eigenbasis = real FFT, eigenvalues in
//                      closed form  lambda_k = sum_j col[j] cos(2 pi j k / N), k = 0..N/2
//   dense(m)           M symmetric PSD     eigendecomposition once, here
//   grid(axes, shift)  M = shift I + sum_a (-D2_a) on an n_1 x ... x n_k tensor grid, D2_a the
//                      second difference along axis a (periodic, Dirichlet or Neumann ends);
//                      eigenbasis = a separable real transform per axis (real FFT, DST-I,
//                      DCT-II), eigenvalues in closed form; no d x d matrix is ever formed
// The factories validate (finite; symmetric; positive semi-definite) and throw erkn::Error
// saying how far off the input is. A Stiffness is immutable and cheap to copy (shared data).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace erkn {

/// One axis of a tensor grid: n unknowns spaced `spacing` apart, with the boundary condition
/// that closes the second difference (x_{j-1} - 2 x_j + x_{j+1}) / spacing^2 at both ends.
/// Eigenvalues mu_k of -D2 in the order of the axis transform's coordinates k = 0..n-1:
///   periodic   x_{-1} = x_{n-1}, x_n = x_0                    real FFT, halfcomplex order
///              (FFTW R2HC: k <= n/2 cosine, k > n/2 sine of wave number n-k)
///              mu_k = 4/spacing^2 sin^2(pi w / n), w = min(k, n-k)
///   dirichlet  x_{-1} = x_n = 0 (the n points are interior)  DST-I (FFTW RODFT00)
///              mu_k = 4/spacing^2 sin^2(pi (k+1) / (2(n+1)))
///   neumann    x_{-1} = x_0, x_n = x_{n-1} (cell-centred:     DCT-II (FFTW REDFT10; inverse
///              zero flux through the faces half a cell out)   DCT-III)
///              mu_k = 4/spacing^2 sin^2(pi k / (2n))
/// (The node-centred Neumann operator that DCT-I diagonalises is not symmetric, so it has no
/// place in q'' + M q = -grad U with symmetric M; the cell-centred one is.)
struct GridAxis {
  enum class Boundary { periodic, dirichlet, neumann };
  Eigen::Index n = 0;
  double spacing = 1;
  Boundary boundary = Boundary::periodic;
  /// mu_0..mu_{n-1} above (closed form).
  Eigen::VectorXd eigenvalues() const;
  /// The boundary called "periodic", "dirichlet" or "neumann"; erkn::Error naming the three else.
  static Boundary boundary_named(const std::string& name);
};

class Stiffness {
 public:
  enum class Structure { scalar, diagonal, circulant, dense, grid };

  /// M = omega2 * I in any dimension; omega2 >= 0.
  static Stiffness scalar(double omega2);
  /// M = diag(m), m >= 0.
  static Stiffness diagonal(const Eigen::VectorXd& m);
  /// Circulant M given by its first column; must satisfy col[j] = col[N-j] (symmetry).
  static Stiffness circulant(const Eigen::VectorXd& first_column);
  /// Dense symmetric positive semi-definite M (decomposed once: O(d^3)).
  static Stiffness dense(const Eigen::MatrixXd& m);
  /// M = shift I - sum_a D2_a on the tensor grid axes[0] x ... x axes[k-1] (k >= 1), d = prod n_a.
  /// Unknowns in row-major (C) order, the last axis fastest: q[(i_0 n_1 + i_1) n_2 + i_2].
  /// shift is Klein-Gordon's mass term m^2; M must be PSD: shift + sum_a min mu_a >= 0.
  static Stiffness grid(std::vector<GridAxis> axes, double shift = 0.0);

  Structure structure() const;
  /// Dimension d of M; 0 for scalar (it fits any dimension).
  Eigen::Index dim() const;
  /// The eigenvalues the coefficients are evaluated at, one per coordinate of the eigenbasis:
  /// scalar: {omega2}; diagonal: m; circulant: lambda_0..lambda_{N/2}; dense: ascending;
  /// grid: shift + sum_a mu_a[k_a] for every multi-index k in row-major order (d entries).
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
  /// Grid only: the axes (empty otherwise) and the shift (0 otherwise).
  const std::vector<GridAxis>& axes() const;
  double shift() const;
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
