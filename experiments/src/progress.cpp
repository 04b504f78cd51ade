#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace ex {
namespace {

double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Progress::Progress(long total)
    : total_(total), enabled_(isatty(STDOUT_FILENO) != 0), start_(wall_seconds()) {}

Progress::~Progress() { finish(); }

void Progress::advance(const std::string& label) {
  ++done_;
  label_ = label;
  draw();
}

void Progress::label(const std::string& label) {
  label_ = label;
  draw();
}

void Progress::finish() {
  if (drawn_) std::printf("\n");
  drawn_ = false;
  std::fflush(stdout);
}

void Progress::draw() {
  if (!enabled_) return;
  constexpr int kWidth = 30;
  const double frac = total_ > 0 ? std::min(1.0, double(done_) / double(total_)) : 0;
  const int filled = int(frac * kWidth);
  std::printf("\r[%.*s%*s] %3d%% %5.0fs  %-40.40s", filled, "##############################",
              kWidth - filled, "", int(100 * frac), wall_seconds() - start_, label_.c_str());
  std::fflush(stdout);
  drawn_ = true;
}

}  // namespace ex
