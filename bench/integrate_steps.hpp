// erkn_integrate_benchmark's step-count check (issue 17: no explicit method needs more steps
// than the peer to reach 1e-6): on sine-Gordon N = 2048 over [0, 1], the fewest steps n (from
// 8, 11, 16, 23, ... ratio sqrt 2) with which the specialist's loop reaches a max-norm error in
// q of 1e-6, and whether erkn accepts h = 1 / n and reaches it too. Reference: the peer with
// SRKN14a (order 6) at 4096 steps, its own accuracy stated (against 2048 steps).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "integrate_cells.hpp"

namespace bench {

struct StepsCell {
  std::string method;
  long peer_steps = 0;  // fewest steps to 1e-6 (0: not within 16384)
  bool erkn_accepts = false;
  double erkn_error = NAN;  // at peer_steps
  std::string refusal;      // erkn's message when it refuses
};
struct StepsCheck {
  std::string scene;
  double target = 1e-6, reference_accuracy = 0;
  std::vector<StepsCell> cells;
};

inline StepsCheck steps_to_target() {
  StepsCheck out;
  const erkn::problems::Problem p = erkn::problems::sine_gordon(2048);
  out.scene = "sine-Gordon N = 2048, t in [0, 1]";
  const specialist::FourierBasis basis = fourier_basis(p.M);
  auto peer_q = [&](const erkn::Method& m, long n) {
    specialist::Peer run(m.table().c, m.table().d, m.stages(), 1.0 / double(n), basis,
                         SineGordonGradient{}, p.q0, p.p0);
    run.run(n);
    Eigen::VectorXd q, v;
    run.state(q, v);
    return q;
  };
  const erkn::Method& best = erkn::Method::by_name("SRKN14a");
  const Eigen::VectorXd ref = peer_q(best, 4096);
  out.reference_accuracy = (peer_q(best, 2048) - ref).lpNorm<Eigen::Infinity>();
  const erkn::System sys = erkn::problems::system(p);
  for (const erkn::Method& m : erkn::Method::all()) {
    if (!m.is_explicit() || m.has_modified_kicks() || m.is_processed())
      continue;  // (the peer's kicks: grad U, no processor)
    StepsCell c{std::string(m.name())};
    for (int k = 0; c.peer_steps == 0; ++k) {
      const long n = std::lround(8 * std::pow(2.0, k / 2.0));
      if (n > 16384) break;
      if ((peer_q(m, n) - ref).lpNorm<Eigen::Infinity>() <= out.target) c.peer_steps = n;
    }
    if (c.peer_steps > 0) try {
        erkn::Integrator run(m, sys, 1.0 / double(c.peer_steps), p.q0, p.p0);
        run.integrate(1.0);
        c.erkn_accepts = true;
        c.erkn_error = (run.q() - ref).lpNorm<Eigen::Infinity>();
      } catch (const erkn::Error& e) {
        c.refusal = e.what();
      }
    out.cells.push_back(c);
  }
  return out;
}

}  // namespace bench
