// The stage solver's space (runtime/src/serial_space.hpp describes the concept) for an M
// distributed over MPI ranks (a grid in slabs, a circulant M in blocks: distributed_transform.hpp):
// the arrays are this rank's part of the eigen coordinates and of the physical vectors; reduce sums
// every rank's parts in one MPI_Allreduce, which also carries the check that every rank's gradient
// since the last reduce was good, so all ranks take every decision together and an error on one
// rank is an error on all of them. It is also the transform of the library's explicit stepper
// (runtime/src/explicit_stepper.hpp: spectral_size, forward, inverse, staging, apply_M, and the
// deferred checks gradient, to_eigen_force, defer, settle).
#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <array>
#include <exception>
#include <string>

#include "collective.hpp"
#include "distributed_transform.hpp"
#include "erkn/system.hpp"
#include "stage_checks.hpp"       // (runtime/src)
#include "step_coefficients.hpp"  // (runtime/src)

namespace erkn::mpi::detail {

class SlabSpace {
 public:
  using Spectral = Eigen::ArrayXd;
  using Scalar = double;
  using Array = Eigen::ArrayXd;
  using Map = Eigen::Map<Eigen::ArrayXd, Eigen::AlignedMax>;
  template <int slots>
  using Block = Eigen::ArrayXd;
  static constexpr bool kDenseNewton = false;  // (no rank holds a d x d Jacobian)
  static constexpr bool kFixed = false;        // (the dimension is not a compile-time constant)

  /// rkn: add_MQ adds M Q (the force of RKN methods).
  SlabSpace(MPI_Comm comm, DistributedTransform& T, bool rkn)
      : comm_(comm),
        T_(T),
        stride_(erkn::detail::aligned_stride<double>(T.spectral_size())),
        rkn_(rkn) {}

  Eigen::Index dimension() const { return T_.physical_size(); }
  Eigen::Index size() const { return T_.spectral_size(); }
  Eigen::Index spectral_size(Eigen::Index /*d*/) const { return size(); }  ///< (a transform's)
  template <int slots>
  Block<slots> block(int count) const {
    return Eigen::ArrayXd::Zero(count * stride_);
  }
  template <class B>
  Map map(B& block, int k) const {
    return map(block.data(), k);
  }
  Map map(double* first, int k) const { return Map(first + k * stride_, size()); }
  template <class V>
  static const V& co(const V& value) {
    return value;
  }

  // Collective transforms (one all-to-all each).
  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    Eigen::Ref<Eigen::ArrayXd> out(y);
    T_.forward(x, out);
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    Eigen::Ref<Eigen::VectorXd> out(x);
    T_.inverse(y, out);
  }
  /// The transform's staging (distributed_transform.hpp): the explicit stepper's flow writes the
  /// stage there, and inverse_staged transforms it without a copy (collective).
  double* staging() { return T_.staging(); }
  double staging_scale() const { return T_.staging_scale(); }
  void inverse_staged(Eigen::VectorXd& x) { T_.inverse_staged(x); }
  template <class Y>
  void to_physical(const Y& y, Eigen::VectorXd& x) {
    inverse(y, x);
  }
  template <class Y>
  void to_eigen(const Eigen::VectorXd& x, Y&& y) {
    forward(x, y);
  }
  /// G = forward(g) + Lambda Q_hat for RKN methods (M is diagonal in eigen coordinates: no more
  /// transforms).
  template <class Y, class G>
  void to_eigen_force(const Eigen::VectorXd& /*Q*/, const Y& Q_hat, Eigen::VectorXd& g, G&& G_hat) {
    forward(g, G_hat);
    if (rkn_) G_hat += T_.eigenvalues() * Q_hat;
  }

  // This rank's parts of the sums (Parseval's weights in eigen coordinates).
  template <class Y>
  double squared_norm(const Y& y) const {
    return (T_.weights() * y.square()).sum();
  }
  template <class A, class B>
  static double dot(const A& a, const B& b) {
    return a.dot(b);
  }
  template <class A>
  static double squared_physical_norm(const A& a) {
    return a.squaredNorm();
  }
  /// Collective: the sums over every rank (one MPI_Allreduce); throws the gradient errors of any
  /// rank since the last reduce on every rank.
  template <size_t n>
  std::array<double, n> reduce(const std::array<double, n>& sums) const {
    std::array<double, n + 1> all{};
    for (size_t k = 0; k < n; ++k) all[k] = sums[k];
    all[n] = error_.empty() ? 0.0 : 1.0;
    MPI_Allreduce(MPI_IN_PLACE, all.data(), int(n + 1), MPI_DOUBLE, MPI_SUM, comm_);
    unchecked_ = false;
    if (all[n] > 0) gradient_failed();
    std::array<double, n> out;
    for (size_t k = 0; k < n; ++k) out[k] = all[k];
    return out;
  }
  double reduce_max(double x) const {
    MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MAX, comm_);
    return x;
  }
  /// Collective after a stage's last evaluation: its checks (when no reduce followed it).
  void settle() const {
    if (unchecked_) reduce(std::array<double, 0>{});
  }

  /// g = grad U(Q) on this slab; a failure (a non-finite Q, a callback that throws or returns a
  /// non-finite g or one of the wrong size) is kept for the next reduce, g zeroed meanwhile.
  void gradient(const System& system, const Eigen::VectorXd& Q, Eigen::VectorXd& g, int i,
                const erkn::detail::StepPlace& at, long& evaluations);
  void add_MQ(const Eigen::VectorXd& Q, Eigen::VectorXd& g);
  /// y = M x (collective: through the eigenbasis, where M is diagonal).
  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y);
  /// Keeps a failed check of this rank, as gradient keeps a failure, for the next reduce.
  void defer(const std::exception& e);

 private:
  [[noreturn]] void gradient_failed() const;
  void keep(std::string message);  // (this rank's first failure since the last reduce)

  MPI_Comm comm_;
  DistributedTransform& T_;
  Eigen::Index stride_;
  bool rkn_;
  // (mutable: a reduce, which reads only sums, also reports and clears the pending failures)
  mutable bool unchecked_ = false;  // an evaluation since the last reduce
  mutable std::string error_;       // this rank's first failure since the last reduce
  Eigen::ArrayXd MQ_hat_;           // (add_MQ)
  Eigen::VectorXd MQ_;
};

}  // namespace erkn::mpi::detail
