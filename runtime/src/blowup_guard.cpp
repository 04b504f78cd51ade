#include "blowup_guard.hpp"

#include <cmath>
#include <limits>

#include "format.hpp"

namespace erkn::detail {

void BlowupGuard::start(bool on) {
  on_ = pending_ = on;
  countdown_ = kInterval;
}

void BlowupGuard::set_reference(bool energy, double measure, double scale) {
  energy_ = energy;
  reference_ = measure;
  scale_ = scale;
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

}  // namespace erkn::detail
