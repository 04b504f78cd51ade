// `erkn CMD --help` (or -h): the command prints its usage to stdout and exits 0; a usage error
// prints the same text to stderr and exits 2.
#pragma once

#include <iostream>
#include <string_view>

namespace erkn::cli {

inline bool asks_for_help(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string_view a = argv[i]; a == "--help" || a == "-h") return true;
  return false;
}

/// Prints `text` as asked (help: stdout, exit 0) or as a usage error (stderr, exit 2).
inline int print_usage(std::string_view text, bool help) {
  (help ? std::cout : std::cerr) << text;
  return help ? 0 : 2;
}

}  // namespace erkn::cli
