// Writing generated/: the method list (X-macro), the tables (C++), and a readable derivation.
#pragma once

#include <string>
#include <vector>

#include "derive.hpp"

namespace erkn::gen {

/// Writes every file under `outdir`; `command` goes into the banners.
void emit(const std::vector<Derived>& methods, const std::string& outdir,
          const std::string& command);

/// A user's methods: writes `outdir`/erkn_methods.cpp (their tables, added to erkn's registry
/// at program start) and `outdir`/derivation.md; `specs` names the spec files in the banners.
void emit_user(const std::vector<Derived>& methods, const std::string& outdir,
               const std::string& command, const std::string& specs);

/// The explicit methods as data (Method::load): JSON with c, d to 25 significant digits, the
/// certified order and generalized order. Throws for a method that is not explicit.
std::string methods_json(const std::vector<Derived>& methods);

}  // namespace erkn::gen
