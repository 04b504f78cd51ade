// Writing generated/: the method list (X-macro), the tables (C++), and a readable derivation.
#pragma once

#include <string>
#include <vector>

#include "derive.hpp"

namespace erkn::gen {

/// Writes every file under `outdir`; `command` goes into the banners.
void emit(const std::vector<Derived>& methods, const std::string& outdir,
          const std::string& command);

}  // namespace erkn::gen
