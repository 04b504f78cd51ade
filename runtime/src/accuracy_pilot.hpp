// The pilot of an accuracy-driven run (erkn/accuracy.hpp): a method stepped on the user's own
// problem with h and h/2 over a short interval, the step-doubling error estimate grown to t_end,
// and the measured cost per gradient evaluation.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "erkn/integrator.hpp"

namespace erkn::detail {

/// The shape of a method's global error in h, sum_k c_k h^(g_k) with c_k > 0 (the a priori
/// model up to a factor): increasing in h, and ln shape is convex in ln h.
struct ErrorShape {
  std::vector<double> c, g;
  double operator()(double h) const;
  /// The h <= h_max with shape(h) = level (h_max when shape(h_max) <= level): Newton's method
  /// on ln shape in ln h from the smallest h where one term alone reaches the level (or h_max),
  /// which converges monotonically from there (ln shape is convex, and above the level).
  double step_at(double level, double h_max) const;
};

/// Method m's shape, sum_K r^K C_K h^(g_K) from the certified generalized orders g_K and the
/// generator's error constants C_K; C h^p where those are unknown; empty when no constant is.
ErrorShape error_shape(const Method& m, double r);

/// The values sorted, each once (to 1e-12 relative): the advisor's findings depend on an
/// eigenvalue's value only, and a grid's M repeats most (2-D sine-Gordon 32^2: 1024, 152 distinct).
Eigen::VectorXd distinct(const Eigen::VectorXd& values);

struct PilotRequest {
  const System* system = nullptr;
  const Eigen::VectorXd* q0 = nullptr;
  const Eigen::VectorXd* p0 = nullptr;
  Options options;
  double span = 0;   ///< t_end - t0
  double pilot = 0;  ///< the pilot interval, <= span
  /// The method's error shape: its slope is the order the step doubling and the extrapolation
  /// in h assume.
  ErrorShape shape;
};

struct Pilot {
  bool ok = false;
  std::string failure;  ///< why the last attempt failed (ok == false)
  double h = 0;
  double interval = 0;          ///< the accepted attempt's pilot interval (n h)
  double error = 0;             ///< estimated max-norm error of q at t_end of the run with step h
  bool at_roundoff = false;     ///< the h and h/2 runs differ only by round-off
  double cpu = 0;               ///< CPU seconds of all attempts
  long gradients = 0;           ///< gradient evaluations of all attempts
  double cpu_per_gradient = 0;  ///< of the accepted attempt
};

/// A run's q at checkpoints: after every `every`-th of n steps of size h from (q0, p0), and
/// after the last.
struct Track {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> q;
  long gradients = 0;
};
Track run(const Method& method, const PilotRequest& request, double h, long n, long every);

/// Pilots `method` from h_start, refining h until the estimate lies within a factor 1000 of
/// `target` (above it: finer; below it: coarser, and once at two steps a 4x longer pilot
/// interval, up to the span; at most 8 attempts).
Pilot calibrated_pilot(const Method& method, const PilotRequest& request, double h_start,
                       double target);

/// The step reaching `target` from a pilot: shape(h) = shape(h_pilot) target / error, at most
/// 4 h_pilot when the pilot sat at round-off, at most the span.
double step_for(const PilotRequest& request, const Pilot& pilot, double target);

/// The growth probe (accuracy_growth.cpp): `probe` stepped with h and h/2 over 1/8 of the span
/// (at least 16 steps); its step-doubling envelope's growth from the pilot interval to the
/// probe's end, extrapolated as t^beta (beta in [0, 1] from the probe's last two octaves), over
/// the linear growth span / pilot_interval the pilot assumed: relief in [pilot / span, 1].
/// 1 when the probe would not reach past 2 pilot intervals, blows up or sits at round-off.
struct Growth {
  double relief = 1;   ///< the measured growth over the pilot's linear one
  long gradients = 0;  ///< of the probe
};
Growth growth_relief(const Method& probe, const PilotRequest& request, double h,
                     double pilot_interval);

/// The probe's number of steps of h.
long probe_steps(const PilotRequest& request, double h);

/// The order the shape has at h: log2(shape(h) / shape(h/2)), at least 1.
double order_at(const PilotRequest& request, double h);

}  // namespace erkn::detail
