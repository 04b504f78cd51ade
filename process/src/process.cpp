#include "erkn/process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "erkn/error.hpp"

namespace erkn::process {
namespace {

struct Pipe {
  int fd[2] = {-1, -1};
  Pipe() {
    if (pipe2(fd, O_CLOEXEC) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  }
  ~Pipe() { close_both(); }
  void close_end(int i) {
    if (fd[i] >= 0) close(fd[i]), fd[i] = -1;
  }
  void close_both() { close_end(0), close_end(1); }
};

// In the child (after fork): only async-signal-safe calls, then exec or _exit(127).
[[noreturn]] void start_child(const Request& r, char* const* argv, Pipe& in, Pipe& out, Pipe& err) {
  if (dup2(in.fd[0], 0) < 0 || dup2(out.fd[1], 1) < 0 || dup2(err.fd[1], 2) < 0) _exit(127);
  if (!r.working_directory.empty() && chdir(r.working_directory.c_str()) != 0) {
    const char message[] = "cannot change to the working directory\n";
    (void)!write(2, message, sizeof message - 1);
    _exit(127);
  }
  execvp(argv[0], argv);
  const char message[] = "cannot start the program\n";
  (void)!write(2, message, sizeof message - 1);
  _exit(127);
}

// Feeds stdin and drains stdout/stderr until both close or the deadline passes.
bool pump(const Request& r, Pipe& in, Pipe& out, Pipe& err, Result& result) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(r.timeout_seconds);
  size_t written = 0;
  if (r.input.empty()) in.close_end(1);
  char buffer[4096];
  while (out.fd[0] >= 0 || err.fd[0] >= 0) {
    pollfd fds[3] = {{out.fd[0], POLLIN, 0}, {err.fd[0], POLLIN, 0}, {in.fd[1], POLLOUT, 0}};
    int wait_ms = -1;
    if (r.timeout_seconds > 0) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (left.count() <= 0) return false;
      wait_ms = int(left.count());
    }
    if (poll(fds, 3, wait_ms) < 0 && errno != EINTR) return false;
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = read(fds[k].fd, buffer, sizeof buffer);
      if (n > 0)
        (k == 0 ? result.out : result.err).append(buffer, size_t(n));
      else if (n == 0 || errno != EINTR)
        (k == 0 ? out : err).close_end(0);
    }
    if (fds[2].fd >= 0 && (fds[2].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t n = write(in.fd[1], r.input.data() + written, r.input.size() - written);
      if (n > 0) written += size_t(n);
      if (n < 0 && errno != EINTR) in.close_end(1);  // (the program closed its stdin)
      if (written == r.input.size()) in.close_end(1);
    }
  }
  return true;
}

// Waits for the child (killing it at the deadline, also if it lingers after closing its
// output) and returns its wait status.
int finish(pid_t pid, const Request& r, bool pumped, Result& result) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(r.timeout_seconds);
  int status = 0;
  for (;;) {
    if (!pumped || (r.timeout_seconds > 0 && Clock::now() > deadline)) {
      kill(pid, SIGKILL);
      result.timed_out = true;
      while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return status;
    }
    const pid_t done = waitpid(pid, &status, r.timeout_seconds > 0 ? WNOHANG : 0);
    if (done == pid) return status;
    if (done < 0 && errno != EINTR) return status;
    if (done == 0) usleep(2000);
  }
}

}  // namespace

Result run(const Request& r) {
  if (r.argv.empty()) throw Error("process::run: no program given");
  std::vector<char*> argv;
  for (const std::string& a : r.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  Pipe in, out, err;
  // A program that closes its stdin early must not kill us with SIGPIPE.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &previous);
  const pid_t pid = fork();
  if (pid < 0) {
    sigaction(SIGPIPE, &previous, nullptr);
    throw Error("cannot start " + r.argv[0] + ": fork: " + std::strerror(errno));
  }
  if (pid == 0) start_child(r, argv.data(), in, out, err);
  in.close_end(0), out.close_end(1), err.close_end(1);
  Result result;
  const int status = finish(pid, r, pump(r, in, out, err, result), result);
  sigaction(SIGPIPE, &previous, nullptr);
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status) && !result.timed_out) result.signal = WTERMSIG(status);
  return result;
}

void run_checked(const Request& r) {
  const Result result = run(r);
  if (result.ok()) return;
  std::string command;
  for (const std::string& a : r.argv) command += (command.empty() ? "" : " ") + a;
  const std::string status = result.timed_out ? "timed out"
                             : result.signal
                                 ? "was killed by signal " + std::to_string(result.signal)
                                 : "exited with " + std::to_string(result.exit_code);
  throw Error("'" + command + "' (in " +
              (r.working_directory.empty() ? std::string(".") : r.working_directory) + ") " +
              status + (result.err.empty() ? std::string() : ": " + result.err));
}

}  // namespace erkn::process
