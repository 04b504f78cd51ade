#include "run_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "erkn/error.hpp"

namespace erkn::cli {
namespace {

namespace fs = std::filesystem;

// The experiments program that belongs to this erkn: the build tree's when this is the build
// tree's erkn, else the one installed beside it (never a build tree's from an installed erkn,
// never a search of PATH).
fs::path experiments_program() {
  std::error_code ec;
  const fs::path self = fs::canonical("/proc/self/exe", ec);
  if (ec) throw Error("erkn run: cannot locate the erkn executable: " + ec.message());
#if defined(ERKN_BUILD_TREE_ERKN) && defined(ERKN_BUILD_TREE_EXPERIMENTS)
  if (fs::equivalent(self, ERKN_BUILD_TREE_ERKN, ec)) return ERKN_BUILD_TREE_EXPERIMENTS;
#endif
  return self.parent_path() / "erkn-experiments";
}

}  // namespace

int run_command(int argc, char** argv) {
  const std::string program = experiments_program().string();
  std::vector<char*> args{const_cast<char*>(program.c_str())};
  for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv(program.c_str(), args.data());
  throw Error("erkn run: cannot start " + program + ": " + std::strerror(errno) +
              " (it is built with -DERKN_BUILD_EXPERIMENTS=ON and installed beside erkn)");
}

}  // namespace erkn::cli
