// Minimal JSON writing for the CLI: numbers with 17 significant digits, lists, strings.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace erkn::cli {

inline std::string json_number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// A number, or null for NaN (JSON has no NaN).
inline std::string json_number_or_null(double x) { return std::isnan(x) ? "null" : json_number(x); }

inline std::string json_list(const std::vector<double>& xs) {
  std::string out = "[";
  for (size_t i = 0; i < xs.size(); ++i) out += (i ? ", " : "") + json_number(xs[i]);
  return out + "]";
}

inline std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) out += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
  return out + "\"";
}

}  // namespace erkn::cli
