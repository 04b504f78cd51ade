#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace ex {
namespace {

double wall_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

Progress::Progress(long total)
    : total_(total),
      enabled_(isatty(STDOUT_FILENO) != 0),
      start_(wall_seconds()),
      unit_start_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(const std::string& label) {
  ++done_;
  record(label);
  label_ = label;
  draw();
}

void Progress::record(const std::string& unit) {
  const double now = wall_seconds();
  units_.emplace_back(unit, now - unit_start_);
  unit_start_ = now;
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

void Progress::write_unit_seconds(const std::filesystem::path& file) const {
  auto sorted = units_;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::ofstream f(file);
  if (!f) throw std::runtime_error("cannot write " + file.string());
  f << "unit,wall_seconds\n";
  for (const auto& [unit, seconds] : sorted) f << '"' << unit << "\"," << seconds << '\n';
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
