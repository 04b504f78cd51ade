// The splitting peer: a Composition run in M's eigen coordinates. q and p stay in those
// coordinates between steps; a kick maps q to physical coordinates, evaluates grad U there and
// maps the gradient back (two transforms for a circulant M, none for scalar or diagonal M).
#include "splitting.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include "eigen_coordinates.hpp"

namespace ex {
namespace {

using Array = Eigen::ArrayXd;

/// The exact flow over a fraction a of the step: per coordinate with omega^2 = lambda,
/// q <- cos(a h w) q + sin(a h w)/w p,  p <- -w sin(a h w) q + cos(a h w) p.
struct LinearFlow {
  Array cos_, sin_over_w, w_sin;
};

LinearFlow linear_flow(const Vec& lambda, double t) {
  LinearFlow f{Array(lambda.size()), Array(lambda.size()), Array(lambda.size())};
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    const double w = std::sqrt(lambda[k]), x = w * t;
    f.cos_[k] = std::cos(x);
    f.sin_over_w[k] = w == 0 ? t : std::sin(x) / w;
    f.w_sin[k] = w * std::sin(x);
  }
  return f;
}

/// Eigenvalues of M, refusing negative ones (beyond round-off of a zero eigenvalue).
Vec checked_lambda(const Vec& lambda, const std::string& method) {
  const double scale = std::max(1.0, lambda.cwiseAbs().maxCoeff());
  if (lambda.minCoeff() < -1e-12 * scale)
    throw std::runtime_error(method + ": M has a negative eigenvalue (" +
                             std::to_string(lambda.minCoeff()) + ")");
  return lambda.cwiseMax(0.0);
}

/// |tr S(0, z)| > 2 for the composition on y'' = -eps y, z = h^2 eps, in (y, h y'): a flow of
/// fraction a is [[1, a], [0, 1]], a kick of weight b is [[1, 0], [-b z, 1]] (mollified kicks
/// are unfiltered at V = 0).
bool unstable_at(const Composition& c, double z) {
  Eigen::Matrix2d s = Eigen::Matrix2d::Identity(), kick0, flow;
  for (size_t i = 0; i < c.flow.size(); ++i) {
    kick0 << 1, 0, -c.kick[i] * z, 1;
    flow << 1, c.flow[i], 0, 1;
    s = flow * kick0 * s;
  }
  kick0 << 1, 0, -c.kick.back() * z, 1;
  s = kick0 * s;
  return !(std::abs(s.trace()) <= 2);
}

class SplittingPeer : public Solver {
 public:
  explicit SplittingPeer(Composition c) : c_(std::move(c)) {
    if (c_.kick.size() != c_.flow.size() + 1)
      throw std::logic_error(c_.name + ": a composition needs one kick more than flows");
  }
  std::string name() const override { return c_.name; }
  Family family() const override { return Family::peer; }
  bool is_explicit() const override { return true; }
  int order() const override { return c_.order; }
  bool exact_for_linear_part() const override { return true; }
  bool suits_grid() const override { return c_.for_grids; }
  std::optional<double> first_unstable_z() const override {
    return ex::first_unstable_z([this](double z) { return unstable_at(c_, z); });
  }

  RunResult run(const Problem& pr, double h, long steps, const Observer* obs) const override {
    EigenCoordinates basis(pr.M, pr.dim());
    const Vec lambda = checked_lambda(basis.lambda(), c_.name);
    // One flow table per distinct fraction (the compositions are palindromes).
    std::map<double, LinearFlow> tables;
    std::vector<const LinearFlow*> flows;
    for (double a : c_.flow)
      flows.push_back(&tables.try_emplace(a, linear_flow(lambda, a * h)).first->second);
    Array filter;  // sinc(h omega) per coordinate
    if (c_.filtered)
      filter = lambda.array().sqrt().unaryExpr(
          [h](double w) { return w * h == 0 ? 1.0 : std::sin(w * h) / (w * h); });

    RunResult r{pr.q0, pr.p0, {}};
    Vec q, p, qf, g, grad(pr.dim()), phys(pr.dim());
    Array q_old;
    basis.to(pr.q0, q);
    basis.to(pr.p0, p);
    auto evaluate = [&] {  // g = T grad U(T^{-1} q), mollified when filtered
      if (c_.filtered) {
        qf = (filter * q.array()).matrix();
        basis.from(qf, phys);
      } else {
        basis.from(q, phys);
      }
      pr.grad_u(phys, grad);
      basis.to(grad, g);
      if (c_.filtered) g.array() *= filter;
      ++r.stats.grad_evals;
    };
    const size_t m = c_.flow.size();
    const bool fsal = c_.kick.front() != 0 && c_.kick.back() != 0;
    bool g_valid = false;  // g belongs to the current q
    for (long n = 0; n < steps; ++n) {
      if (c_.kick.front() != 0) {
        if (!g_valid) evaluate();
        p.noalias() -= (h * c_.kick.front()) * g;
      }
      for (size_t i = 0; i < m; ++i) {
        const LinearFlow& f = *flows[i];
        q_old = q.array();
        q.array() = f.cos_ * q_old + f.sin_over_w * p.array();
        p.array() = f.cos_ * p.array() - f.w_sin * q_old;
        if (c_.kick[i + 1] == 0) continue;
        evaluate();
        p.noalias() -= (h * c_.kick[i + 1]) * g;
      }
      g_valid = fsal;
      ++r.stats.steps;
      if (obs) {
        basis.from(q, r.q);
        basis.from(p, r.p);
        (*obs)(double(n + 1) * h, r.q, r.p);
      }
    }
    basis.from(q, r.q);
    basis.from(p, r.p);
    return r;
  }

 private:
  Composition c_;
};

}  // namespace

std::optional<double> first_unstable_z(const std::function<bool(double z)>& unstable) {
  double previous = 0;
  for (double z = 0.01; z <= 1e4; z *= 1.02) {
    if (unstable(z)) {
      double lo = previous, hi = z;
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        (unstable(mid) ? hi : lo) = mid;
      }
      return hi;
    }
    previous = z;
  }
  return std::nullopt;
}

std::unique_ptr<Solver> make_splitting(Composition composition) {
  return std::make_unique<SplittingPeer>(std::move(composition));
}

SolverList make_splitting_peers() {
  SolverList list;
  for (Composition c :
       {strang(), blanes_moan_srkn6b(), blanes_moan_srkn14a(), aba1064(), mollified_impulse()})
    list.push_back(make_splitting(std::move(c)));
  return list;
}

}  // namespace ex
