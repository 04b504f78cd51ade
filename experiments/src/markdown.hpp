// Number and name formatting shared by the markdown the run writes (results.md, summary.md).
#pragma once

#include <optional>
#include <string>

#include "summary.hpp"

namespace ex {

/// printf-style formatting of one number.
std::string fmt(const char* format, double x);
/// "1.23e-06", or "failed" for a non-finite number.
std::string sci(double x);
/// "2.35×".
std::string times(double ratio);
/// "2.35× [2.20–2.51]": a ratio and its range over the interleaved timing rounds, if measured.
std::string times(const Ratio& ratio);
/// "0.476 (2.80×)": a value with its ratio to a reference, or "—" without a value.
std::string with_ratio(const std::optional<double>& value, const std::optional<double>& reference,
                       const char* format);
/// The kind column: "ERKN", "explicit ERKN", "RKN limit" or "peer".
std::string kind_name(const SolverTraits& traits);

}  // namespace ex
