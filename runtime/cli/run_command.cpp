#include "run_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <vector>

#include "erkn/error.hpp"

namespace erkn::cli {

int run_command(int argc, char** argv) {
#ifdef ERKN_EXPERIMENTS
  const char* program = ERKN_EXPERIMENTS;  // the build tree's erkn-experiments
#else
  const char* program = "erkn-experiments";  // installed next to erkn, found on PATH
#endif
  std::vector<char*> args{const_cast<char*>(program)};
  for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execvp(program, args.data());
  throw Error(std::string("erkn run: cannot start ") + program + ": " + std::strerror(errno) +
              " (build with -DERKN_BUILD_EXPERIMENTS=ON)");
}

}  // namespace erkn::cli
