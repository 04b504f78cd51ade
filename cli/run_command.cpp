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

// The experiments program that belongs to this erkn: the one beside it, in the build tree (bin/)
// as where both are installed (never a search of PATH).
fs::path experiments_program() {
  std::error_code ec;
  const fs::path self = fs::canonical("/proc/self/exe", ec);
  if (ec) throw Error("erkn run: cannot locate the erkn executable: " + ec.message());
  const fs::path program = self.parent_path() / "erkn-experiments";
  if (!fs::exists(program, ec))
    throw Error("erkn run needs the experiments program " + program.string() +
                ", which is missing: it is built with -DERKN_BUILD_EXPERIMENTS=ON (cmake --build "
                "BUILD --target erkn-experiments) and installed beside erkn");
  return program;
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
