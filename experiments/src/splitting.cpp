// The splitting peer: a Composition run in M's eigen coordinates. q and p stay in those
// coordinates between steps; a kick maps q to physical coordinates, evaluates grad U there (and
// for a modified kick 2 Hess U grad U) and maps it back (two transforms for a circulant M, none
// for scalar or diagonal M). A processed composition steps its kernel and shows pi of its state.
#include "splitting.hpp"

#include <algorithm>
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
/// fraction a is [[1, a], [0, 1]], a kick of weight b (modified: e) is [[1, 0], [-(b z + 2 e z^2),
/// 1]] (U = eps y^2 / 2: G = 2 eps^2 y; mollified kicks are unfiltered at V = 0). A processor
/// conjugates S and leaves its trace alone.
bool unstable_at(const Composition& c, double z) {
  auto kick = [&](size_t i) {
    const double e = c.modified.empty() ? 0 : c.modified[i];
    Eigen::Matrix2d k;
    k << 1, 0, -(c.kick[i] * z + 2 * e * z * z), 1;
    return k;
  };
  Eigen::Matrix2d s = Eigen::Matrix2d::Identity(), flow;
  for (size_t i = 0; i < c.flow.size(); ++i) {
    flow << 1, c.flow[i], 0, 1;
    s = flow * kick(i) * s;
  }
  s = kick(c.flow.size()) * s;
  return !(std::abs(s.trace()) <= 2);
}

/// One run's state in eigen coordinates and the operations a composition is made of.
class Stepper {
 public:
  Stepper(const Composition& c, const Problem& pr, double h)
      : c_(c),
        pr_(pr),
        h_(h),
        basis_(pr.M, pr.dim()),
        lambda_(checked_lambda(basis_.lambda(), c.name)) {
    if (c_.filtered)
      filter_ = lambda_.array().sqrt().unaryExpr(
          [h](double w) { return w * h == 0 ? 1.0 : std::sin(w * h) / (w * h); });
    for (double a : c_.flow) kernel_flows_.push_back(&table(a));
    grad_.resize(pr.dim()), phys_.resize(pr.dim()), hv_.resize(pr.dim());
    basis_.to(pr.q0, q_);
    basis_.to(pr.p0, p_);
    apply(c_.processor, 1);  // pi^-1
  }

  /// One step of the kernel; the first kick reuses the last one's evaluation (FSAL).
  void step() {
    const size_t m = c_.flow.size();
    if (c_.kick.front() != 0) kick(0, c_.kick.front());
    for (size_t i = 0; i < m; ++i) {
      flow(*kernel_flows_[i]);
      if (c_.kick[i + 1] != 0) kick(i + 1, c_.kick[i + 1]);
    }
    g_valid_ = c_.kick.front() != 0 && c_.kick.back() != 0;
    ++stats.steps;
  }

  /// The state a user sees, in physical coordinates: pi of the stepped state (on a copy).
  void output(Vec& q, Vec& p) {
    if (c_.processor.kick.empty()) {
      basis_.from(q_, q), basis_.from(p_, p);
      return;
    }
    const Vec q0 = q_, p0 = p_, g0 = g_, G0 = G_;
    const bool g_valid = g_valid_, G_valid = G_valid_;
    apply(c_.processor, -1);
    basis_.from(q_, q), basis_.from(p_, p);
    q_ = q0, p_ = p0, g_ = g0, G_ = G0, g_valid_ = g_valid, G_valid_ = G_valid;
  }

  RunStats stats;

 private:
  const LinearFlow& table(double a) {
    return tables_.try_emplace(a, linear_flow(lambda_, a * h_)).first->second;
  }

  void flow(const LinearFlow& f) {
    q_old_ = q_.array();
    q_.array() = f.cos_ * q_old_ + f.sin_over_w * p_.array();
    p_.array() = f.cos_ * p_.array() - f.w_sin * q_old_;
    g_valid_ = G_valid_ = false;
  }

  /// p -= h b g + h^3 e G at the current q (e: the kernel's modified[i], or the processor's).
  void kick(size_t i, double b) { kick_with(b, c_.modified.empty() ? 0 : c_.modified[i]); }
  void kick_with(double b, double e) {
    if (!g_valid_) evaluate();
    p_.noalias() -= (h_ * b) * g_;
    if (e == 0) return;
    if (!G_valid_) evaluate_modified_force();
    p_.noalias() -= (h_ * h_ * h_ * e) * G_;
  }

  /// pi^-1 (sign 1): flow z_0, kick y_0, flow z_1, ...; pi (sign -1): the reverse, negated.
  void apply(const Processor& pi, double sign) {
    const size_t n = pi.kick.size();
    for (size_t j = 0; j < n; ++j) {
      const size_t i = sign > 0 ? j : n - 1 - j;
      if (sign > 0) flow(table(pi.flow[i]));
      kick_with(sign * pi.kick[i], sign * pi.modified[i]);
      if (sign < 0) flow(table(-pi.flow[i]));
    }
  }

  void evaluate();
  void evaluate_modified_force();

  const Composition& c_;
  const Problem& pr_;
  const double h_;
  EigenCoordinates basis_;
  const Vec lambda_;
  Array filter_, q_old_;                 // filter_: sinc(h omega) per coordinate
  std::map<double, LinearFlow> tables_;  // one flow table per distinct fraction
  std::vector<const LinearFlow*> kernel_flows_;
  Vec q_, p_, g_, G_, grad_, phys_, hv_, qf_;
  bool g_valid_ = false, G_valid_ = false;  // g_ (G_) belongs to the current q_
};

/// g = T grad U(T^{-1} q), mollified when filtered.
void Stepper::evaluate() {
  if (c_.filtered) {
    qf_ = (filter_ * q_.array()).matrix();
    basis_.from(qf_, phys_);
  } else {
    basis_.from(q_, phys_);
  }
  pr_.grad_u(phys_, grad_);
  basis_.to(grad_, g_);
  if (c_.filtered) g_.array() *= filter_;
  ++stats.grad_evals;
  g_valid_ = true;
}

/// G = T 2 Hess U grad U at T^{-1} q (after evaluate(): phys_ and grad_ belong to q).
void Stepper::evaluate_modified_force() {
  pr_.hessian_vector_u(phys_, grad_, hv_);
  hv_ *= 2;
  basis_.to(hv_, G_);
  G_valid_ = true;
}

class SplittingPeer : public Solver {
 public:
  explicit SplittingPeer(Composition c) : c_(std::move(c)) {
    if (c_.kick.size() != c_.flow.size() + 1)
      throw std::logic_error(c_.name + ": a composition needs one kick more than flows");
    const Processor& pi = c_.processor;
    if (pi.flow.size() != pi.kick.size() || pi.modified.size() != pi.kick.size() ||
        !(c_.modified.empty() || c_.modified.size() == c_.kick.size()))
      throw std::logic_error(c_.name + ": processor or modified-kick sizes do not match");
    if (c_.filtered && (!c_.modified.empty() || !pi.kick.empty()))
      throw std::logic_error(c_.name + ": mollified kicks are plain, unprocessed kicks");
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
    if (needs_modified_force() && !pr.hessian_vector_u)
      throw std::runtime_error(c_.name + ": " + pr.title + " has no hessian_vector_u");
    Stepper s(c_, pr, h);
    RunResult r{pr.q0, pr.p0, {}};
    for (long n = 0; n < steps; ++n) {
      s.step();
      if (obs) {
        s.output(r.q, r.p);
        (*obs)(double(n + 1) * h, r.q, r.p);
      }
    }
    s.output(r.q, r.p);
    r.stats = s.stats;
    return r;
  }

 private:
  bool needs_modified_force() const {
    auto nonzero = [](const std::vector<double>& x) {
      return std::any_of(x.begin(), x.end(), [](double e) { return e != 0; });
    };
    return nonzero(c_.modified) || nonzero(c_.processor.modified);
  }

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

std::vector<Composition> splitting_peer_compositions() {
  return {strang(),  blanes_moan_srkn6b(), blanes_moan_srkn14a(),
          aba1064(), mollified_impulse(),  omf4_3f3g(),
          pmlf6()};
}

SolverList make_splitting_peers() {
  SolverList list;
  for (Composition c : splitting_peer_compositions()) list.push_back(make_splitting(std::move(c)));
  return list;
}

}  // namespace ex
