// The space of one process (the stage solver's concept, stage_solver.hpp): M's eigenbasis
// (Transform), the arrays of eigen coordinates, the physical vectors the callbacks see, and the
// reductions a step needs, which are the local sums themselves (nothing to combine). D: the
// dimension when it is a compile-time constant (tiny systems with M's identity eigenbasis: the
// arrays then live inside the stepper and every pass over them unrolls).
//
// A space provides: Scalar, Array, Map (a view of one array of eigen coordinates), Block (storage
// for a number of arrays) and block/map to carve it; co(coefficient); forward/inverse (to_eigen,
// to_physical on the stage path); squared_norm(y) (this process's part of |inverse(y)|^2),
// dot/squared_norm of physical vectors, reduce({sums...}) and reduce_max(x) over every process;
// gradient (the user's callback with its checks), add_MQ (g += M Q) and to_eigen_force (the
// stage's force in eigen coordinates, M Q added where it is cheapest); settle() after a stage's
// last evaluation; kDenseNewton (whether a d x d Jacobian may be formed); kFixed (whether Array
// has a compile-time size: the stage solver then iterates on values, stage_solver.hpp's Work).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>

#include "erkn/system.hpp"
#include "implicit_passes.hpp"
#include "m_operator.hpp"
#include "stage_checks.hpp"
#include "step_coefficients.hpp"
#include "transforms.hpp"

namespace erkn::detail {

template <class Transform, int D = Eigen::Dynamic>
class SerialSpace {
 public:
  using Spectral = typename Transform::Spectral;
  using Scalar = typename Spectral::Scalar;
  static constexpr bool kFixed = D != Eigen::Dynamic;
  static_assert(!kFixed || std::is_same_v<Transform, IdentityTransform>,
                "a fixed dimension needs the identity basis");
  static constexpr bool kDenseNewton = true;
  static constexpr int kDimension = D;
  // One array in eigen coordinates (aligned when stride keeps it so: in the dynamic storage).
  using Array = std::conditional_t<kFixed, Eigen::Array<Scalar, D, 1>, Spectral>;
  // With a fixed even D every array starts 16-byte aligned (its block is, and it is k D doubles
  // into it), so the maps say so: GCC then folds their loads into the arithmetic (mulpd from
  // memory; an unaligned map's took a movupd each, ~40 of SERKN2s3's ~690 instructions per step
  // at P3, callgrind). (An odd D: entries are not vectorised.)
  static constexpr int kAlignment =
      !kFixed ? Eigen::AlignedMax : (D % 2 == 0 ? Eigen::Aligned16 : Eigen::Unaligned);
  using Map = Eigen::Map<Array, kAlignment>;
  // Storage for up to `slots` arrays: one allocation, or (fixed dimension) inside its owner,
  // not cleared (the constructor's empty body: its owners, the stepper, the stage solver and the
  // predictor, write every array before they read it; value-initialised, the predictor's
  // kMaxNodes arrays were a rep stos of 448 bytes at D = 2, ~1 % of the time of a construct +
  // 1-step run of SERKN2s3 at P3, perf).
  template <int slots>
  struct FixedBlock {
    FixedBlock() {}
    Scalar* data() { return values.data(); }
    std::array<Scalar, slots * std::max(D, 1)> values;
  };
  template <int slots>
  using Block = std::conditional_t<kFixed, FixedBlock<slots>, Spectral>;

  /// M: the stiffness applied by add_MQ (RKN methods), d the dimension.
  SerialSpace(Transform transform, const Stiffness& M, Eigen::Index d, bool rkn)
      : transform_(std::move(transform)),
        M_(M, d),
        d_(d),
        m_(transform_.spectral_size(d)),
        stride_(kFixed ? D : aligned_stride<Scalar>(m_)),
        rkn_(rkn) {
    if (rkn_) Mq_.setZero(d), set_m_diagonal(M);
    if constexpr (kStagedIterate) transform_.weight();  // (made now: steps allocate nothing)
  }

  Eigen::Index dimension() const { return d_; }  ///< physical entries (of this process)
  Eigen::Index size() const { return m_; }       ///< eigen coordinates (of this process)

  template <int slots>
  Block<slots> block(int count) const {
    if constexpr (kFixed)
      return Block<slots>();
    else
      return Spectral::Zero(count * stride_);
  }
  /// The k-th array of a block, or of the arrays from first on.
  template <class B>
  Map map(B& block, int k) const {
    return map(block.data(), k);
  }
  Map map(Scalar* first, int k) const {
    if constexpr (kFixed)
      return Map(first + k * D);  // (the stride a constant: no load and multiply per view)
    else
      return Map(first + k * stride_, m_);
  }

  // A coefficient as a pass reads it (implicit_passes.hpp): a number, or its values.
  static double coefficient_of(double value) { return value; }
  template <class V>
  static const double* coefficient_of(const V& value) {
    return value.data();
  }

  // A coefficient as the arrays see it: a number, or an array map (of fixed size when D is, so
  // that expressions mixing it with the stage arrays keep the fixed size).
  template <class V>
  static auto co(const V& value) {
    if constexpr (kFixed && !std::is_same_v<V, double>)
      return Eigen::Map<const Eigen::Array<double, D, 1>, kAlignment>(value.data());
    else
      return value;
  }

  template <class X, class Y>
  void forward(const X& x, Y&& y) {
    transform_.forward(x, y);
  }
  template <class Y, class X>
  void inverse(const Y& y, X&& x) {
    transform_.inverse(y, x);
  }
  // x = inverse(y) and y = forward(x) of the stage path; with a fixed D, fixed-size copies.
  template <class Y>
  void to_physical(const Y& y, Eigen::VectorXd& x) {
    if constexpr (kFixed)
      Eigen::Map<Array>(x.data()) = y;
    else
      transform_.inverse(y, x);
  }
  template <class Y>
  void to_eigen(const Eigen::VectorXd& x, Y&& y) {
    transform_.forward(x, y);
  }

  /// A transform with a staging buffer (HalfSpectrumTransform) takes the fixed point's iterate
  /// in one pass (iterate: implicit_passes.hpp's iterate_pass): Q_new = r - abar g, this
  /// process's {squared_norm(Q_new - Q), squared_norm(Q_new)}, and Q_new staged, which
  /// to_physical_staged then transforms.
  static constexpr bool kStagedIterate = requires(Transform & t) { t.staging(); };
  template <class R, class A, class G, class Q, class Out>
  std::array<double, 2> iterate(const R& r, const A& abar, const G& g, const Q& Q_hat, Out& Q_new) {
    const auto lanes = [](const auto& x) { return reinterpret_cast<const double*>(x.data()); };
    const auto sums = iterate_pass(m_, lanes(r), coefficient_of(abar), lanes(g), lanes(Q_hat),
                                   reinterpret_cast<double*>(Q_new.data()), transform_.staging(),
                                   transform_.staging_scale(), transform_.weight().data());
    return {sums[0], sums[1]};
  }
  void to_physical_staged(Eigen::VectorXd& x) { transform_.inverse_staged(x); }
  /// The stage's start (kStagedIterate; implicit_passes.hpp's start_passes): r = phi0c q +
  /// hcphi1c p - sum_{j<i} abar_ij G_j (term(j): G_j and abar_ij), Q_0 = r - abar_ii guess staged;
  /// returns this process's squared_norm(Q_0).
  template <class Y, class A, class Term, class Out>
  double start(int i, const Y& q, const Y& p, const A& phi0c, const A& hcphi1c, const A& abar_ii,
               Term&& term, const Out& guess, Out& r, Out& Q0) {
    const auto in = [](const auto& x) { return reinterpret_cast<const double*>(x.data()); };
    const auto out = [](Out& x) { return reinterpret_cast<double*>(x.data()); };
    const StartTerms t{in(q),
                       in(p),
                       nullptr,
                       in(guess),
                       out(r),
                       out(Q0),
                       transform_.staging(),
                       transform_.staging_scale(),
                       transform_.weight().data()};
    return start_passes(i, m_, t, coefficient_of(phi0c), coefficient_of(hcphi1c),
                        coefficient_of(abar_ii), [&](int j) {
                          const auto [G, abar_ij] = term(j);
                          return std::pair{in(G), coefficient_of(abar_ij)};
                        });
  }
  /// G = forward(g + M Q) of the stage path (g += M Q for RKN methods: in physical coordinates,
  /// where it is a stencil or an inline product). With a fixed D g is left as the callback wrote
  /// it (the stage solver may scan it after the iteration, checked_iterate) and read entry by
  /// entry into registers (callback_entries: no vector load spanning the callback's scalar
  /// stores): plus m_k Q_k for M scalar or diagonal, else plus M Q (the sums add_MQ forms).
  /// (Always inlined: GCC left it out of line at D = 2, its G through memory: P3 +13 % CPU.)
  template <class Y, class G>
  [[gnu::always_inline]] void to_eigen_force(const Eigen::VectorXd& Q, const Y& Q_hat,
                                             Eigen::VectorXd& g, G&& G_hat) {
    if constexpr (kFixed) {
      if (!rkn_) {
        G_hat = callback_entries<D>(g.data());
      } else if (m_diagonal_) {
        G_hat = callback_entries<D>(g.data()) + m_diag_ * Q_hat;
      } else {
        M_.apply(Q, Mq_);
        G_hat = callback_entries<D>(g.data()) + Eigen::Map<const Array>(Mq_.data());
      }
    } else {
      add_MQ(Q, g);
      to_eigen(g, G_hat);
    }
  }

  // |inverse(y)|^2.
  template <class Y>
  double squared_norm(const Y& y) const {
    return transform_.squared_norm(y);
  }
  // Physical vectors.
  template <class A, class B>
  static double dot(const A& a, const B& b) {
    return a.dot(b);
  }
  template <class A>
  static double squared_physical_norm(const A& a) {
    return a.squaredNorm();
  }
  /// The sums over every process: here, the sums themselves.
  template <size_t n>
  static std::array<double, n> reduce(const std::array<double, n>& sums) {
    return sums;
  }
  static double reduce_max(double x) { return x; }

  /// g = grad U(Q) with the checks of stage_checks.hpp (errors thrown here, at once; the
  /// finiteness of g only when check_g, of Q only when check_Q). (Always inlined: with the stage
  /// inlined into the step GCC left it out of line at D = 2, ~40 more instructions per grad U, P3.
  /// g's size checked against D itself when it is fixed: d_ was reloaded after every call.)
  [[gnu::always_inline]] void gradient(const System& system, const Eigen::VectorXd& Q,
                                       Eigen::VectorXd& g, int i, const StepPlace& at,
                                       long& evaluations, bool check_g = true,
                                       bool check_Q = true) const {
    checked_gradient<D>(system.gradient, Q, g, kFixed ? D : d_, i, at, evaluations, check_g,
                        check_Q);
  }
  void settle() const {}  // (nothing deferred)
  void add_MQ(const Eigen::VectorXd& Q, Eigen::VectorXd& g);
  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) { M_.apply(x, y); }

 private:
  void set_m_diagonal(const Stiffness& M);

  Transform transform_;
  MOperator M_;
  Eigen::Index d_, m_, stride_;
  bool rkn_;
  Eigen::VectorXd Mq_;
  bool m_diagonal_ = false;  // RKN, fixed D, M scalar or diagonal: M = diag(m_diag_)
  Eigen::Array<double, kFixed ? D : 1, 1> m_diag_;
};

// g += M Q (RKN methods only). With a fixed D and a scalar or diagonal M inline, g_k += m_k Q_k:
// the products MOperator::apply forms, without its call and the pass over Mq_ (P2, D = 1: 15-18 %
// less CPU per evaluation for RKN1s2(1), RKN2s4, RKN3s4(1); a driver stepping the Stepper alone).
template <class Transform, int D>
void SerialSpace<Transform, D>::add_MQ(const Eigen::VectorXd& Q, Eigen::VectorXd& g) {
  if (!rkn_) return;
  if constexpr (kFixed) {
    if (m_diagonal_) {
      Eigen::Map<Array>(g.data()) += m_diag_ * Eigen::Map<const Array>(Q.data());
      return;
    }
  }
  M_.apply(Q, Mq_);
  g += Mq_;
}

// m_diag_ for add_MQ: M's diagonal when it is scalar or diagonal (fixed D only).
template <class Transform, int D>
void SerialSpace<Transform, D>::set_m_diagonal(const Stiffness& M) {
  using S = Stiffness::Structure;
  if constexpr (kFixed) {
    if (M.structure() == S::scalar) m_diag_.setConstant(M.entries()[0]);
    if (M.structure() == S::diagonal) m_diag_ = M.entries().array();
    m_diagonal_ = M.structure() == S::scalar || M.structure() == S::diagonal;
  }
}

}  // namespace erkn::detail
