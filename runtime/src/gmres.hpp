// Restarted GMRES(m), matrix-free and right-preconditioned (Saad, Iterative Methods for Sparse
// Linear Systems, alg. 9.5): solves J x = b from x = 0 with J applied as apply(v, Jv) and the
// preconditioner as precondition(v, P^{-1} v); the residual |b - J x| is that of J itself.
// Dot products and norms are the space's (serial_space.hpp): each sums this process's part and
// reduces it over all processes, so the vectors may be the local parts of a distributed one.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace erkn::detail {

class Gmres {
 public:
  /// The Krylov basis holds `restart` + 1 vectors of size d (allocated here, once).
  Gmres(Eigen::Index d, int restart)
      : m_(restart),
        V_(d, restart + 1),
        Z_(d, restart),
        H_(restart + 1, restart),
        w_(d),
        cs_(restart),
        sn_(restart),
        g_(restart + 1),
        y_(restart) {}

  /// Iterates until |b - J x| <= rtol |b| or max_iterations applications of J; returns the
  /// relative residual reached.
  template <class Apply, class Precondition, class Space>
  double solve(Apply&& apply, Precondition&& precondition, const Space& space,
               const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, int max_iterations) {
    const auto dot = [&](const auto& u, const auto& v) {
      return space.reduce(std::array{space.dot(u, v)})[0];
    };
    const auto norm = [&](const auto& u) {
      return std::sqrt(space.reduce(std::array{space.squared_physical_norm(u)})[0]);
    };
    x.setZero(b.size());
    const double norm_b = norm(b);
    if (norm_b == 0) return 0;
    double residual = 1;
    int used = 0;
    w_ = b;  // the residual of x = 0
    while (used < max_iterations) {
      double beta = norm(w_);
      residual = beta / norm_b;
      if (residual <= rtol) break;
      V_.col(0) = w_ / beta;
      g_.setZero();
      g_[0] = beta;
      int k = 0;
      for (; k < m_ && used < max_iterations; ++k, ++used) {
        precondition(V_.col(k), Z_.col(k));
        apply(Z_.col(k), w_);
        for (int j = 0; j <= k; ++j) {  // modified Gram-Schmidt
          H_(j, k) = dot(V_.col(j), w_);
          w_ -= H_(j, k) * V_.col(j);
        }
        H_(k + 1, k) = norm(w_);
        if (H_(k + 1, k) > 0) V_.col(k + 1) = w_ / H_(k + 1, k);
        for (int j = 0; j < k; ++j) rotate(j, H_(j, k), H_(j + 1, k));
        const double r = std::hypot(H_(k, k), H_(k + 1, k));
        cs_[k] = r == 0 ? 1 : H_(k, k) / r;
        sn_[k] = r == 0 ? 0 : H_(k + 1, k) / r;
        H_(k, k) = r;
        H_(k + 1, k) = 0;
        rotate(k, g_[k], g_[k + 1]);
        residual = std::abs(g_[k + 1]) / norm_b;
        if (residual <= rtol) {
          ++k, ++used;
          break;
        }
      }
      // x += Z y with H y = g (upper triangular, k columns).
      y_.head(k) = H_.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g_.head(k));
      x += Z_.leftCols(k) * y_.head(k);
      if (residual <= rtol || !std::isfinite(residual)) break;
      apply(x, w_);  // restart from the true residual
      w_ = b - w_;
    }
    return residual;
  }

 private:
  void rotate(int j, double& a, double& b) const {
    const double t = cs_[j] * a + sn_[j] * b;
    b = -sn_[j] * a + cs_[j] * b;
    a = t;
  }

  int m_;
  Eigen::MatrixXd V_, Z_, H_;
  Eigen::VectorXd w_, cs_, sn_, g_, y_;
};

}  // namespace erkn::detail
