// The processor of a processed method psi = pi o K o pi^-1 (docs/design.md, "Processing";
// erkn/table.hpp, Table::pre_drift): the explicit stepper keeps the kernel K's state and steps
// it; set_state applies pi^-1 (the table's pre-sequence: drift, kick, ..., drift) to the user's
// state, get_state applies pi (the same sequence reversed, every drift and kick negated, its
// exact inverse) to a copy. These are the operations and coefficients of one application, for
// one h: per drift its exact flow over tau = pre_drift[k] h (cos, sin(w tau)/w, -w sin(w tau)
// per eigenvalue), per kick its weights y_k and h^2 v_k. A drift run backwards has the same
// cos and the negated sines.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "erkn/method.hpp"

namespace erkn::detail {

class ProcessorCoefficients {
 public:
  struct Drift {
    Eigen::ArrayXd cos, sinc, msinc;  // (one entry for a scalar M: the same for every coordinate)
  };
  struct Kick {
    double y = 0, h2v = 0;  // p -= h (y grad U + h2v G) (h2v = 0: a plain kick)
  };

  /// lambda: M's eigenvalue of each eigen coordinate (or one for a scalar M). Empty when the
  /// method is not processed.
  ProcessorCoefficients(const Method& method, double h, const Eigen::VectorXd& lambda) {
    const generated::Table& t = method.table();
    for (int k = 0; k < t.npre; ++k) kicks_.push_back({t.pre_kick[k], h * h * t.pre_modified[k]});
    for (int k = 0; method.is_processed() && k <= t.npre; ++k) {
      const double tau = h * t.pre_drift[k];
      const Eigen::ArrayXd w = lambda.array().sqrt();
      Drift f{(w * tau).cos(), Eigen::ArrayXd(w.size()), -lambda.array()};
      for (Eigen::Index e = 0; e < w.size(); ++e)
        f.sinc[e] = w[e] == 0 ? tau : std::sin(w[e] * tau) / w[e];
      f.msinc *= f.sinc;
      drifts_.push_back(std::move(f));
    }
  }

  int kicks() const { return int(kicks_.size()); }
  const Drift& drift(int k) const { return drifts_[size_t(k)]; }
  const Kick& kick(int k) const { return kicks_[size_t(k)]; }

 private:
  std::vector<Drift> drifts_;
  std::vector<Kick> kicks_;
};

}  // namespace erkn::detail
