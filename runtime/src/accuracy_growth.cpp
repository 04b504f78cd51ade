// The growth probe of an accuracy-driven run (erkn/accuracy.hpp): how the global error grows
// after the pilot interval, measured with a cheap method over a longer interval.
//
// Why: the pilot sees a few steps, and its estimate grows their error linearly to t_end, the
// bound for local errors that never cancel. On the benchmark's scenes the error after t_end/32
// grows like that on Henon-Heiles, but hardly at all on sine-Gordon (P1) and FPU, where the
// linear estimate was 20-120x the achieved error (docs/accuracy.md, 'estimate / error'). The
// growth law (bounded, linear, in between) belongs to the flow's linearisation along the orbit,
// not to the method, so a cheap method's step-doubling error shows it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "accuracy_pilot.hpp"
#include "erkn/error.hpp"

namespace erkn::detail {
namespace {

// The step-doubling differences |q_h - q_h/2| at every `every`-th step up to n steps of h.
struct Envelope {
  std::vector<double> t, e;
  double roundoff = 0;  // the level below which e is round-off
  long gradients = 0;
  // max e over t in [a, b]
  double max(double a, double b) const {
    double m = 0;
    for (size_t i = 0; i < t.size(); ++i)
      if (t[i] >= a * (1 - 1e-12) && t[i] <= b * (1 + 1e-12)) m = std::max(m, e[i]);
    return m;
  }
};

// The step-doubling differences of the pilot's runs (accuracy_pilot.cpp's run) with h and h/2.
Envelope envelope(const Method& m, const PilotRequest& r, double h, long n, long every) {
  const Track a = run(m, r, h, n, every), b = run(m, r, h / 2, 2 * n, 2 * every);
  Envelope out;
  for (size_t i = 0; i < a.q.size() && i < b.q.size(); ++i) {
    const double size = a.q[i].lpNorm<Eigen::Infinity>();
    out.t.push_back(a.t[i]), out.e.push_back((a.q[i] - b.q[i]).lpNorm<Eigen::Infinity>());
    out.roundoff =
        std::max(out.roundoff, 128 * std::numeric_limits<double>::epsilon() * a.t[i] / h * size);
  }
  out.gradients = a.gradients + b.gradients;
  return out;
}

}  // namespace

Growth growth_relief(const Method& probe, const PilotRequest& r, double h, double pilot_interval) {
  const long n = probe_steps(r, h);
  Growth out;
  if (2 * pilot_interval > double(n) * h || double(n) * h > r.span) return out;
  try {
    const Envelope env = envelope(probe, r, h, n, std::max(1L, n / 64));
    out.gradients = env.gradients;
    const double tq = env.t.back(), at_pilot = env.max(0, std::max(pilot_interval, env.t[0]));
    const double late = env.max(tq / 2, tq), early = env.max(tq / 8, tq / 4);
    if (!(early > env.roundoff && at_pilot > env.roundoff)) return out;
    // G: the error's growth from the pilot's end to t_end: as measured to tq, then as t^beta,
    // beta in [0, 1] from the probe's last two octaves (its envelope over [tq/8, tq/4] and
    // [tq/2, tq]); the pilot's linear estimate grew by span / pilot_interval.
    const double beta = std::clamp(std::log(late / early) / std::log(4.0), 0.0, 1.0);
    const double G = env.max(0, tq) / at_pilot * std::pow(r.span / tq, beta);
    if (std::isfinite(G)) out.relief = std::min(1.0, G * pilot_interval / r.span);
  } catch (const Error&) {  // the probe blew up: no evidence, keep the linear estimate
  }
  return out;
}

long probe_steps(const PilotRequest& r, double h) {
  return std::max(16L, std::lround(r.span / 8 / h));  // over 1/8 of the span, 4x the pilot's
}

}  // namespace erkn::detail
