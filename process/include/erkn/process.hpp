// Starting another program without a shell: fork + exec with the arguments as a vector, stdin fed
// and stdout/stderr collected through pipes, an optional working directory and time limit.
// Used by `erkn stability` and the experiments' charts (gnuplot) and by the CLI tests.
#pragma once

#include <string>
#include <vector>

namespace erkn::process {

struct Request {
  std::vector<std::string> argv;  ///< argv[0] is looked up on PATH (execvp)
  std::string working_directory;  ///< "" = the caller's
  std::string input;              ///< written to the program's stdin, which is then closed
  double timeout_seconds = 0;     ///< > 0: the program is killed (SIGKILL) when it runs longer
};

struct Result {
  int exit_code = -1;  ///< when it exited normally (127: it could not be started)
  int signal = 0;      ///< the signal that ended it, else 0
  bool timed_out = false;
  std::string out, err;
  bool ok() const { return exit_code == 0 && signal == 0 && !timed_out; }
};

/// Runs the program to its end; throws erkn::Error only when no process can be created.
Result run(const Request& request);

/// Runs the program and throws erkn::Error naming it, its exit status and its stderr unless it
/// exits with 0.
void run_checked(const Request& request);

}  // namespace erkn::process
