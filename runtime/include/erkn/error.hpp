// erkn::Error: the one exception type of the library. Every message names the problem.
#pragma once

#include <stdexcept>
#include <string>

namespace erkn {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error("erkn: " + what) {}
};

}  // namespace erkn
