// Reading generator/methods.spec: one block of `key value` lines per method.
#pragma once

#include <istream>
#include <string>
#include <vector>

namespace erkn::gen {

struct MethodSpec {
  std::string name;     ///< the paper's name, e.g. "SERKN3s4(1)"
  std::string rkn;      ///< the name of its V -> 0 limit
  std::string section;  ///< where the paper derives it
  int stages = 0;
  int order = 0;
  std::vector<std::string> c;         ///< GiNaC syntax, or "?" for a node solved by the generator
  std::vector<std::string> diagonal;  ///< equations `lhs == rhs` fixing abar_ii
};

/// C identifier for a method name: "SERKN3s4(1)" -> "SERKN3s4_1".
std::string identifier(const std::string& name);

/// Throws std::runtime_error naming the line of a malformed spec.
std::vector<MethodSpec> read_specs(std::istream& in);

}  // namespace erkn::gen
