#include "markdown.hpp"

#include <cmath>
#include <cstdio>

#include "summary.hpp"

namespace ex {

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string sci(double x) { return std::isfinite(x) ? fmt("%.2e", x) : "failed"; }

std::string times(double ratio) { return fmt("%.2f×", ratio); }

std::string times(const Ratio& r) {
  if (!r.low || !r.high) return times(r.value);
  return times(r.value) + " [" + fmt("%.2f", *r.low) + "–" + fmt("%.2f", *r.high) + "]";
}

std::string with_ratio(const std::optional<double>& v, const std::optional<double>& reference,
                       const char* format) {
  if (!v) return "—";
  std::string s = fmt(format, *v);
  if (const auto r = ratio(v, reference)) s += " (" + times(*r) + ")";
  return s;
}

std::string kind_name(const SolverTraits& t) {
  switch (t.family) {
    case Family::erkn:
      return t.is_explicit ? "explicit ERKN" : "ERKN";
    case Family::rkn:
      return "RKN limit";
    case Family::peer:
      return "peer";
  }
  return "";
}

}  // namespace ex
