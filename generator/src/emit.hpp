// Writing generated/: the method list (X-macro), the tables (C++), and a readable derivation.
#pragma once

#include <string>
#include <vector>

#include "derive.hpp"

namespace erkn::gen {

struct Emittable {
  Derived method;
  std::vector<std::vector<double>> poles;  ///< per coefficient
  std::vector<double> series_switch;       ///< per coefficient: series below, closed form above
};

inline constexpr double kPoleSearchMax = 10000.0;

/// Writes every file under `outdir`; `command` goes into the banners.
void emit(const std::vector<Emittable>& methods, const std::string& outdir,
          const std::string& command);

}  // namespace erkn::gen
