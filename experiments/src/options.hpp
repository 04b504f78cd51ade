// Command line of erkn-experiments.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "experiment.hpp"

namespace ex {

struct Options {
  std::vector<std::string> problems{"P1", "P2", "P3", "FPU", "HH", "scaling", "stiff", "grids"};
  std::vector<std::string> methods;  ///< empty: all
  /// --methods-file F.json (repeatable): a user's explicit methods (erkn-generate --json),
  /// loaded into the registry (erkn::Method::load) before the methods are chosen.
  std::vector<std::string> methods_files;
  std::string mode = "quick";  ///< "quick", "full" or "custom" (with --steps)
  std::filesystem::path out = "docs";
  bool list = false;
  bool help = false;  // --help: print the usage and exit 0
  RunConfig config;
};

/// Parses argv; throws std::invalid_argument with a message naming the bad option.
Options parse_options(int argc, char** argv);
std::string usage();

}  // namespace ex
