#include "blowup_guard.hpp"

#include <cmath>
#include <limits>

#include "format.hpp"

namespace erkn::detail {

void BlowupGuard::start(bool on) {
  on_ = pending_ = on;
  countdown_ = kInterval;
}

void BlowupGuard::set_reference(double H, double scale, bool has_potential) {
  energy_ = has_potential && std::isfinite(H);
  reference_ = energy_ || !has_potential ? H : 0;  // (U(q0) not finite: E_2's first positive value)
  scale_ = energy_ ? scale : 0;
  pending_ = false;
}

double BlowupGuard::growth(double measure) {
  if (!std::isfinite(measure)) return std::numeric_limits<double>::infinity();
  if (energy_) {
    if (scale_ <= 0) scale_ = std::abs(measure - reference_);  // (a zero state: first change)
    return scale_ > 0 ? std::abs(measure - reference_) / scale_ / kEnergyLimit : 0;
  }
  if (reference_ <= 0) reference_ = measure;  // (E_2 = 0 at the start: its first positive value)
  return reference_ > 0 ? measure / reference_ / kGrowthLimit : 0;
}

std::string BlowupGuard::message(double measure, double t, long step, double t_kept,
                                 const std::string& cause) const {
  const std::string what =
      energy_
          ? "the energy error |H - H_0| / scale = " +
                format(std::abs(measure - reference_) / scale_, 3) + " > " + format(kEnergyLimit) +
                " (H = " + format(measure) + ", H_0 = " + format(reference_) +
                ", scale 1/2|p0|^2 + 1/2 q0'M q0 + |U(q0)| = " + format(scale_) + ")"
          : "1/2|p|^2 + 1/2 q'M q = " + format(measure) + " grew by a factor " +
                format(measure / reference_, 3) + " > " + format(kGrowthLimit, 3);
  return "blow-up guard: at t = " + format(t, 12) + " (step " + std::to_string(step) + ") " + what +
         "; the state of the last check, t = " + format(t_kept, 12) + " (step " +
         std::to_string(checkpoint_.steps) + "), is kept. Likely cause: " + cause +
         " (Options::blowup_guard = false switches this check off)";
}

std::string BlowupGuard::cause(const StepSizeAdvice& advice, const Method& method, double h) {
  if (advice.safe() && !advice.equation.empty())
    return "the differential equation's own growth, not the step size, by the step-size "
           "advisor: " +
           advice.report(method);
  if (advice.safe())
    return "not the step size by the step-size advisor (no eigenvalue of M in an unstable "
           "band, at a resonance of an excited mode or near a pole at h = " +
           format(h) +
           " with the Hessian of U at the kept state): a Hessian range or a mode's energy the "
           "kept state does not show";
  return "the step size, by the step-size advisor: " + advice.report(method);
}

}  // namespace erkn::detail
