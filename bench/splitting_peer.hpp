// A hand-written splitting integrator: the exact flow of q'' + M q = 0 over tau_k =
// h (c_k - c_{k-1}) alternated with kicks p -= h d_k grad U(Q_k), the state kept in M's
// eigenbasis, the first kick reusing the previous step's last gradient when c_1 = 0 and c_s = 1.
// It is what a user would write by hand for one explicit method, with no framework: the floor
// the runtime's explicit path is measured against (same nodes, weights and gradient code).
//
// Basis: forward(x, y) physical -> eigen, inverse(y, x) back, lambda() one eigenvalue per
// eigen coordinate. Vec: the array type of one state (fixed size for tiny d).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace bench {

template <class Basis, class Vec, class Gradient>
class SplittingPeer {
 public:
  SplittingPeer(const double* c, const double* d, int s, double h, Basis basis, Gradient gradient,
                const Vec& q0, const Vec& p0)
      : basis_(std::move(basis)),
        gradient_(gradient),
        s_(s),
        fsal_(s > 1 && c[0] == 0 && c[s - 1] == 1) {
    const Vec lambda = basis_.lambda();
    for (int k = 0; k <= s; ++k) {
      const double tau = h * ((k < s ? c[k] : 1.0) - (k > 0 ? c[k - 1] : 0.0));
      Flow f{tau != 0, lambda, lambda, lambda};
      for (Eigen::Index e = 0; e < lambda.size(); ++e) {
        const double w = std::sqrt(lambda[e]), x = w * tau;
        f.cos[e] = std::cos(x);
        f.sinc[e] = w == 0 ? tau : std::sin(x) / w;
        f.msin[e] = -w * std::sin(x);
      }
      flows_.push_back(f);
      if (k < s) hd_.push_back(h * d[k]);
    }
    q_ = q0, p_ = p0, Q_ = q0, g_ = q0, G_ = q0, tmp_ = q0;
    basis_.forward(q0, q_);
    basis_.forward(p0, p_);
  }

  void step() {
    for (int k = 0; k < s_; ++k) {
      flow(flows_[k]);
      if (!(k == 0 && fsal_ && started_)) {
        basis_.inverse(q_, Q_);
        gradient_(Q_, g_);
        basis_.forward(g_, G_);
        ++evaluations_;
      }
      p_ -= hd_[k] * G_;
    }
    flow(flows_[s_]);
    started_ = true;
  }

  Vec q() { return inverse(q_); }
  Vec p() { return inverse(p_); }
  long evaluations() const { return evaluations_; }

 private:
  struct Flow {
    bool moves;
    Vec cos, sinc, msin;  // cos(w tau), sin(w tau)/w, -w sin(w tau)
  };

  void flow(const Flow& f) {
    if (!f.moves) return;
    tmp_ = q_;
    q_ = f.cos * tmp_ + f.sinc * p_;
    p_ = f.msin * tmp_ + f.cos * p_;
  }

  Vec inverse(const Vec& y) {
    Vec x = y;
    basis_.inverse(y, x);
    return x;
  }

  Basis basis_;
  Gradient gradient_;
  int s_;
  bool fsal_, started_ = false;
  std::vector<Flow> flows_;
  std::vector<double> hd_;
  Vec q_, p_, Q_, g_, G_, tmp_;
  long evaluations_ = 0;
};

/// M diagonal: the eigenbasis is the standard basis.
template <class Vec>
struct DiagonalBasis {
  Vec m;
  Vec lambda() const { return m; }
  void forward(const Vec& x, Vec& y) const { y = x; }
  void inverse(const Vec& y, Vec& x) const { x = y; }
};

/// Symmetric circulant M (first column col) on the real orthonormal Fourier basis, folded:
/// x_j +- x_{N-j} against the half-size cosine and sine blocks (N^2/2 multiply-adds a transform).
struct FourierBasis {
  explicit FourierBasis(const Eigen::ArrayXd& col)
      : n(col.size()),
        nc(n / 2 + 1),
        ns((n - 1) / 2),
        C(nc, nc),
        S(ns, ns),
        lam(n),
        even(nc),
        odd(ns) {
    const double pi = 3.14159265358979323846;
    Eigen::ArrayXd cosine(n), sine(n);  // of 2 pi m / N: every angle below reduced mod N
    for (Eigen::Index m = 0; m < n; ++m)
      cosine[m] = std::cos(2 * pi * double(m) / double(n)),
      sine[m] = std::sin(2 * pi * double(m) / double(n));
    const double edge = std::sqrt(1.0 / double(n)), inner = std::sqrt(2.0 / double(n));
    for (Eigen::Index k = 0; k < nc; ++k)
      for (Eigen::Index j = 0; j < nc; ++j)
        C(j, k) = ((k == 0 || 2 * k == n) ? edge : inner) * cosine[(j * k) % n];
    for (Eigen::Index k = 0; k < ns; ++k)
      for (Eigen::Index j = 0; j < ns; ++j) S(j, k) = inner * sine[((j + 1) * (k + 1)) % n];
    for (Eigen::Index k = 0; k < nc; ++k) {
      double l = 0;
      for (Eigen::Index j = 0; j < n; ++j)
        if (col[j] != 0) l += col[j] * cosine[(j * k) % n];
      lam[k] = l;
      if (k >= 1 && k <= ns) lam[nc + k - 1] = l;
    }
  }
  Eigen::ArrayXd lambda() const { return lam; }
  void forward(const Eigen::ArrayXd& x, Eigen::ArrayXd& y) {
    even = x.head(nc).matrix();
    even.segment(1, ns) += x.tail(ns).reverse().matrix();
    odd = (x.segment(1, ns) - x.tail(ns).reverse()).matrix();
    y.head(nc).matrix().noalias() = C.transpose() * even;
    y.tail(ns).matrix().noalias() = S.transpose() * odd;
  }
  void inverse(const Eigen::ArrayXd& y, Eigen::ArrayXd& x) {
    even.noalias() = C * y.head(nc).matrix();
    odd.noalias() = S * y.tail(ns).matrix();
    x.head(nc) = even.array();
    x.segment(1, ns) += odd.array();
    x.tail(ns) = (even.segment(1, ns) - odd).array().reverse();
  }
  Eigen::Index n, nc, ns;
  Eigen::MatrixXd C, S;
  Eigen::ArrayXd lam;
  Eigen::VectorXd even, odd;
};

}  // namespace bench
