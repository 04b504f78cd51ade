// Number formatting for error messages: enough digits to act on.
#pragma once

#include <sstream>
#include <string>

namespace erkn {

inline std::string format(double x, int digits = 10) {
  std::ostringstream os;
  os.precision(digits);
  os << x;
  return os.str();
}

}  // namespace erkn
