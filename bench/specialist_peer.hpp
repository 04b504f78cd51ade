// The exact-flow splitting loop as a specialist writes it for one explicit method (nodes c_i,
// weights d_i): the exact flow of q'' + M q = 0 over h (c_{k+1} - c_k) alternated with kicks
// p -= h d_k grad U(Q_k), with
//   - the state kept in M's eigenbasis for the whole run (FFTW r2c/c2r for a circulant M or a
//     periodic grid, planned once outside the run; the identity for scalar and diagonal M),
//     the 1/N of the unnormalised transforms folded into the state and the kick weights;
//   - adjacent drifts merged across step boundaries: the last flow of a step, h (1 - c_s), and
//     the first of the next, h c_1, are one exact flow over h (1 - c_s + c_1);
//   - when c_1 = 0 and c_s = 1, the last kick of a step and the first of the next merged into
//     one kick with weight h (d_s + d_1) (one gradient per step fewer);
//   - the gradient inlined: a template functor g(q, out) over Eigen arrays; or, wrapped in
//     VectorCallback, called as a user's callback on Eigen::VectorXd (erkn::System::gradient, a
//     std::function): the loop a specialist writes around a gradient it cannot inline, keeping the
//     arrays the gradient reads and writes as Eigen::VectorXd so that the call needs no copies.
// It shares no code with erkn's runtime: what it takes from a method is c and d as numbers.
//
//   bench::specialist::FourierBasis basis = bench::specialist::FourierBasis::circulant(col);
//   bench::specialist::Peer run(c, d, s, h, basis, [](auto& q, auto& g) { g = q.sin(); }, q0, p0);
//   run.run(n);         // n steps
//   run.state(q, p);    // physical coordinates
#pragma once

#include <fftw3.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace bench::specialist {

/// An aligned array of doubles (fftw_malloc: the alignment FFTW's plans were made for).
class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(Eigen::Index n)
      : n_(n), data_(static_cast<double*>(fftw_malloc(sizeof(double) * size_t(n > 0 ? n : 1)))) {
    if (!data_) throw std::bad_alloc();
    std::memset(data_, 0, sizeof(double) * size_t(n));
  }
  Buffer(Buffer&& o) noexcept
      : n_(std::exchange(o.n_, 0)), data_(std::exchange(o.data_, nullptr)) {}
  Buffer& operator=(Buffer&& o) noexcept {
    std::swap(n_, o.n_), std::swap(data_, o.data_);
    return *this;
  }
  Buffer(const Buffer&) = delete;
  ~Buffer() { fftw_free(data_); }
  double* data() { return data_; }
  const double* data() const { return data_; }
  Eigen::Index size() const { return n_; }

 private:
  Eigen::Index n_ = 0;
  double* data_ = nullptr;
};

/// An array of doubles as an Eigen::VectorXd, for a gradient called on Eigen::VectorXd (FFTW's
/// plans here run on it: Eigen's 16 bytes are the alignment FFTW plans for, fftw_alignment_of).
class VectorBuffer {
 public:
  VectorBuffer() = default;
  explicit VectorBuffer(Eigen::Index n) : v_(Eigen::VectorXd::Zero(n)) {}
  double* data() { return v_.data(); }
  const double* data() const { return v_.data(); }
  Eigen::Index size() const { return v_.size(); }
  Eigen::VectorXd& vector() { return v_; }

 private:
  Eigen::VectorXd v_;
};

/// The gradient f(q, g) on Eigen::VectorXd (q const, g sized), called through whatever F is (an
/// erkn::System::gradient: a std::function) rather than inlined.
template <class F>
struct VectorCallback {
  F f;
};
template <class G>
inline constexpr bool kIsVectorCallback = false;
template <class F>
inline constexpr bool kIsVectorCallback<VectorCallback<F>> = true;

/// Scalar or diagonal M: the eigenbasis is the standard basis (D: the dimension when fixed).
template <int D = Eigen::Dynamic>
struct IdentityBasis {
  static constexpr bool kIdentity = true;
  static constexpr int kDim = D;
  Eigen::Array<double, D, 1> m;  // the eigenvalues
  Eigen::Index dim() const { return D == Eigen::Dynamic ? m.size() : D; }
  Eigen::Index spectral_size() const { return dim(); }
  /// The eigenvalue that scales spectral double i.
  double lambda(Eigen::Index i) const { return m[i]; }
};

/// Real symmetric circulant M (1-D) or a periodic grid M = shift - Lap_h (2-D, row-major): the
/// real-input DFT (FFTW r2c/c2r) diagonalises it. The spectral state is the half spectrum as
/// interleaved doubles (re, im per mode), both scaled by that mode's eigenvalue. Plans are made
/// here (FFTW_MEASURE, i.e. from the wisdom after the first basis of a size): outside any run.
class FourierBasis {
 public:
  static constexpr bool kIdentity = false;
  static constexpr int kDim = Eigen::Dynamic;

  /// First column col of a symmetric circulant: lambda_k = sum_j col_j cos(2 pi j k / N).
  static FourierBasis circulant(const Eigen::VectorXd& col) {
    const Eigen::Index n = col.size(), half = n / 2 + 1;
    std::vector<Eigen::Index> stencil;  // the non-zero entries
    for (Eigen::Index j = 0; j < n; ++j)
      if (col[j] != 0) stencil.push_back(j);
    Eigen::ArrayXd lambda = Eigen::ArrayXd::Zero(half);
    for (Eigen::Index k = 0; k < half; ++k)
      for (Eigen::Index j : stencil)
        lambda[k] += col[j] * std::cos(2 * std::numbers::pi * double((j * k) % n) / double(n));
    return FourierBasis({int(n)}, lambda);
  }
  /// M = shift - Lap_h on an n0 x n1 periodic grid with spacings dx0, dx1:
  /// lambda = shift + 4/dx0^2 sin^2(pi k0/n0) + 4/dx1^2 sin^2(pi k1/n1).
  static FourierBasis periodic_grid(int n0, int n1, double dx0, double dx1, double shift) {
    const int half = n1 / 2 + 1;
    Eigen::ArrayXd lambda(Eigen::Index(n0) * half);
    auto mu = [](int k, int n, double dx) {
      const double s = std::sin(std::numbers::pi * k / n);
      return 4 / (dx * dx) * s * s;
    };
    for (int k0 = 0; k0 < n0; ++k0)
      for (int k1 = 0; k1 < half; ++k1)
        lambda[Eigen::Index(k0) * half + k1] = shift + mu(k0, n0, dx0) + mu(k1, n1, dx1);
    return FourierBasis({n0, n1}, lambda);
  }

  FourierBasis(std::vector<int> n, const Eigen::ArrayXd& mode_lambda)
      : n_(std::move(n)), lambda_(2 * mode_lambda.size()) {
    dim_ = 1;
    for (int k : n_) dim_ *= k;
    for (Eigen::Index k = 0; k < mode_lambda.size(); ++k)
      lambda_[2 * k] = lambda_[2 * k + 1] = mode_lambda[k];
    Buffer x(dim_), y(spectral_size());
    auto* yc = reinterpret_cast<fftw_complex*>(y.data());
    forward_ = fftw_plan_dft_r2c(int(n_.size()), n_.data(), x.data(), yc, FFTW_MEASURE);
    inverse_ = fftw_plan_dft_c2r(int(n_.size()), n_.data(), yc, x.data(), FFTW_MEASURE);
  }
  FourierBasis(FourierBasis&& o) noexcept
      : n_(std::move(o.n_)),
        dim_(o.dim_),
        lambda_(std::move(o.lambda_)),
        forward_(std::exchange(o.forward_, nullptr)),
        inverse_(std::exchange(o.inverse_, nullptr)) {}
  FourierBasis(const FourierBasis&) = delete;
  ~FourierBasis() {
    if (forward_) fftw_destroy_plan(forward_), fftw_destroy_plan(inverse_);
  }

  Eigen::Index dim() const { return dim_; }
  Eigen::Index spectral_size() const { return lambda_.size(); }
  double lambda(Eigen::Index i) const { return lambda_[i]; }
  /// inverse(forward(x)) = scale() x.
  double scale() const { return double(dim_); }
  /// y = DFT(x) (x preserved).
  void forward(double* x, double* y) const {
    fftw_execute_dft_r2c(forward_, x, reinterpret_cast<fftw_complex*>(y));
  }
  /// x = inverse DFT(y), unnormalised (y destroyed).
  void inverse(double* y, double* x) const {
    fftw_execute_dft_c2r(inverse_, reinterpret_cast<fftw_complex*>(y), x);
  }

 private:
  std::vector<int> n_;
  Eigen::Index dim_ = 0;
  Eigen::ArrayXd lambda_;
  fftw_plan forward_ = nullptr, inverse_ = nullptr;
};

template <class Basis, class Gradient>
class Peer {
 public:
  using PhysicalMap = Eigen::Map<Eigen::Array<double, Basis::kDim, 1>>;
  using ConstPhysicalMap = Eigen::Map<const Eigen::Array<double, Basis::kDim, 1>>;
  // The arrays the gradient reads and writes (and, as well, the others): Eigen::VectorXd for a
  // callback on Eigen::VectorXd.
  static constexpr bool kCallback = kIsVectorCallback<Gradient>;
  using Storage = std::conditional_t<kCallback, VectorBuffer, Buffer>;

  Peer(const double* c, const double* d, int s, double h, const Basis& basis, Gradient gradient,
       const Eigen::VectorXd& q0, const Eigen::VectorXd& p0)
      : basis_(basis), gradient_(std::move(gradient)), s_(s), n_(basis.spectral_size()) {
    if (s < 1 || h <= 0 || q0.size() != basis.dim() || p0.size() != basis.dim())
      throw std::invalid_argument("specialist::Peer: bad stages, step or initial state size");
    double scale = 1;
    if constexpr (!Basis::kIdentity) scale = basis.scale();
    for (int k = 0; k < s; ++k) hd_.push_back(h * d[k] / scale);
    fsal_ = s > 1 && c[0] == 0 && c[s - 1] == 1;
    pre_ = flow_index(h * c[0]);
    for (int k = 0; k + 1 < s; ++k) inner_.push_back(flow_index(h * (c[k + 1] - c[k])));
    wrap_ = flow_index(h * (1 - c[s - 1] + c[0]));
    post_ = flow_index(h * (1 - c[s - 1]));
    q_ = Storage(n_), p_ = Storage(n_), g_ = Storage(basis.dim());
    if constexpr (!Basis::kIdentity) {
      x_ = Storage(n_), Q_ = Storage(basis.dim()), G_ = Storage(n_);
      for (const double* a : {q_.data(), p_.data(), g_.data(), x_.data(), Q_.data(), G_.data()})
        if (kCallback && fftw_alignment_of(const_cast<double*>(a)) != 0)  // (Buffer: fftw_malloc)
          throw std::runtime_error("specialist::Peer: an array not of FFTW's planned alignment");
    }
    load(q0, q_), load(p0, p_);
  }

  /// n steps of size h.
  void run(long n) {
    for (long step = 0; step < n; ++step) {
      const bool first = step == 0, last = step == n - 1;
      if (first) drift(pre_);
      for (int k = 0; k < s_; ++k) {
        // With c_1 = 0, c_s = 1 the first kick is merged into the previous step's last one.
        if (!(k == 0 && fsal_ && !first)) {
          double w = hd_[size_t(k)];
          if (k == s_ - 1 && fsal_ && !last) w += hd_[0];
          kick(w);
        }
        drift(k + 1 < s_ ? inner_[size_t(k)] : (last ? post_ : wrap_));
      }
    }
  }

  /// The state in physical coordinates.
  void state(Eigen::VectorXd& q, Eigen::VectorXd& p) {
    q.resize(basis_.dim()), p.resize(basis_.dim());
    unload(q_, q), unload(p_, p);
  }
  long evaluations() const { return evaluations_; }

 private:
  struct Flow {  // the exact flow over tau, per spectral double
    double tau;
    Buffer cos, sinc, msin;  // cos(w tau), sin(w tau)/w, -w sin(w tau), w^2 = lambda
  };

  // The flow over tau (shared by equal taus, as in symmetric methods); -1 for tau = 0.
  int flow_index(double tau) {
    if (tau == 0) return -1;
    for (size_t i = 0; i < flows_.size(); ++i)
      if (std::abs(flows_[i].tau - tau) <= 1e-15 * std::abs(tau)) return int(i);
    Flow f{tau, Buffer(n_), Buffer(n_), Buffer(n_)};
    for (Eigen::Index i = 0; i < n_; ++i) {
      const double lambda = std::max(basis_.lambda(i), 0.0);  // (round-off negatives)
      if (i > 0 && !Basis::kIdentity && i % 2 == 1) {         // (im shares re's eigenvalue)
        f.cos.data()[i] = f.cos.data()[i - 1], f.sinc.data()[i] = f.sinc.data()[i - 1];
        f.msin.data()[i] = f.msin.data()[i - 1];
        continue;
      }
      const double w = std::sqrt(lambda), sn = std::sin(w * tau);
      f.cos.data()[i] = std::cos(w * tau);
      f.sinc.data()[i] = w == 0 ? tau : sn / w;
      f.msin.data()[i] = -w * sn;
    }
    flows_.push_back(std::move(f));
    return int(flows_.size()) - 1;
  }

  // The exact flow; in a Fourier basis it also writes the new q into x_, the input the next
  // kick's inverse transform consumes (one store stream instead of a copy pass).
  void drift(int index) {
    if (index < 0) return;
    const Flow& f = flows_[size_t(index)];
    double* __restrict q = q_.data();
    double* __restrict p = p_.data();
    double* __restrict x = x_.data();
    const double* __restrict cs = f.cos.data();
    const double* __restrict sc = f.sinc.data();
    const double* __restrict ms = f.msin.data();
    const Eigen::Index n = Basis::kIdentity ? basis_.dim() : n_;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double qi = q[i], pi = p[i], nq = cs[i] * qi + sc[i] * pi;
      p[i] = ms[i] * qi + cs[i] * pi;
      q[i] = nq;
      if constexpr (!Basis::kIdentity) x[i] = nq;
    }
    fresh_ = true;
  }

  // p -= w grad U(Q) with Q the current q (w = h d, divided by N in a Fourier basis).
  void kick(double w) {
    ++evaluations_;
    if constexpr (Basis::kIdentity) {
      gradient(q_);
      const Eigen::Index dim = basis_.dim();
      PhysicalMap(p_.data(), dim) -= w * PhysicalMap(g_.data(), dim);
    } else {
      if (!fresh_) std::memcpy(x_.data(), q_.data(), sizeof(double) * size_t(n_));
      basis_.inverse(x_.data(), Q_.data());
      gradient(Q_);
      basis_.forward(g_.data(), G_.data());
      double* __restrict p = p_.data();
      const double* __restrict G = G_.data();
      for (Eigen::Index i = 0; i < n_; ++i) p[i] -= w * G[i];
    }
    fresh_ = false;
  }

  // g_ = grad U(Q), Q physical.
  void gradient(Storage& Q) {
    if constexpr (kCallback) {
      gradient_.f(std::as_const(Q.vector()), g_.vector());
    } else {
      PhysicalMap g(g_.data(), basis_.dim());
      gradient_(ConstPhysicalMap(Q.data(), basis_.dim()), g);
    }
  }

  void load(const Eigen::VectorXd& v, Storage& y) {
    if constexpr (Basis::kIdentity) {
      std::memcpy(y.data(), v.data(), sizeof(double) * size_t(v.size()));
    } else {  // y = DFT(v) / N, so that inverse(y) = v
      std::memcpy(Q_.data(), v.data(), sizeof(double) * size_t(v.size()));
      basis_.forward(Q_.data(), y.data());
      Eigen::Map<Eigen::ArrayXd>(y.data(), n_) /= basis_.scale();
    }
  }
  void unload(const Storage& y, Eigen::VectorXd& v) {
    if constexpr (Basis::kIdentity) {
      std::memcpy(v.data(), y.data(), sizeof(double) * size_t(v.size()));
    } else {
      std::memcpy(x_.data(), y.data(), sizeof(double) * size_t(n_));
      basis_.inverse(x_.data(), Q_.data());  // (FFTW's planned alignment: no Eigen vector)
      std::memcpy(v.data(), Q_.data(), sizeof(double) * size_t(v.size()));
      fresh_ = false;
    }
  }

  const Basis& basis_;
  Gradient gradient_;
  int s_;
  Eigen::Index n_;  // spectral doubles
  bool fsal_ = false, fresh_ = false;
  int pre_ = -1, wrap_ = -1, post_ = -1;
  std::vector<int> inner_;
  std::vector<double> hd_;
  std::vector<Flow> flows_;
  Storage q_, p_, g_, x_, Q_, G_;
  long evaluations_ = 0;
};

}  // namespace bench::specialist
