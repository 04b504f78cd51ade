// erkn-ensemble-speedup: wall time and speedup of erkn::Ensemble against the number of threads,
// and a check that every thread count reproduces the one-thread results bit for bit.
//   erkn-ensemble-speedup [--out DIR] [--max-threads T] [--repeats R] [--trajectories K]
// writes DIR/ensemble.md (the table) and DIR/charts/ensemble_speedup.svg (the chart).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <erkn/erkn.hpp>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "svg_chart.hpp"

namespace {

namespace fs = std::filesystem;
using erkn::scaling::Chart;

// The first word of a /proc file (Linux), or "unknown".
std::string first_word(const char* path) {
  std::ifstream f(path);
  std::string word;
  return f >> word ? word : "unknown";
}

struct Settings {
  fs::path out = "docs";
  int max_threads = int(std::max(4u, std::thread::hardware_concurrency()));
  int repeats = 3, trajectories = 24, N = 128;
  double h = 0.01, t_end = 10.0;
  std::string method = "SERKN2s4";
  std::string load = first_word("/proc/loadavg");  // 1-minute load average
  std::string autogroup = first_word("/proc/sys/kernel/sched_autogroup_enabled");
};

Settings parse(int argc, char** argv) {
  Settings s;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw erkn::Error("option " + a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--out")
      s.out = v;
    else if (a == "--max-threads")
      s.max_threads = std::stoi(v);
    else if (a == "--repeats")
      s.repeats = std::stoi(v);
    else if (a == "--trajectories")
      s.trajectories = std::stoi(v);
    else
      throw erkn::Error("unknown option " + a);
  }
  if (s.max_threads < 1 || s.repeats < 1 || s.trajectories < 1)
    throw erkn::Error("--max-threads, --repeats and --trajectories must be >= 1");
  return s;
}

// Trajectory i: periodic sine-Gordon on [-1, 1] (problem 1 at N points), initial velocity
// amplitude 1 + i/K.
erkn::Member member(const Settings& s, std::size_t i) {
  const int N = s.N;
  const double dx = 2.0 / N, pi = std::numbers::pi;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(N);
  col[0] = 2 / (dx * dx), col[1] = col[N - 1] = -1 / (dx * dx);
  erkn::Member m;
  m.system.M = erkn::Stiffness::circulant(col);
  m.system.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
  m.q0 = Eigen::VectorXd::Constant(N, pi);
  m.p0.resize(N);
  const double amplitude = 1 + double(i) / s.trajectories;
  for (int k = 0; k < N; ++k)
    m.p0[k] = amplitude * std::sqrt(double(N)) * (0.01 + std::sin(2 * pi * (k + 1) / N));
  return m;
}

struct Row {
  int threads;
  double best, median;
  double cpu_per_wall;  // process CPU time / wall time of the best repeat: cores actually used
  bool identical;
};

bool identical(const std::vector<erkn::TrajectoryResult>& a,
               const std::vector<erkn::TrajectoryResult>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!a[i].ok() || !b[i].ok() || a[i].q != b[i].q || a[i].p != b[i].p) return false;
  return true;
}

std::vector<Row> measure(const Settings& s) {
  const erkn::Ensemble ensemble(erkn::Method::by_name(s.method), s.h, s.trajectories,
                                [&](std::size_t i) { return member(s, i); });
  std::vector<erkn::TrajectoryResult> serial;
  std::vector<Row> rows;
  for (int threads = 1; threads <= s.max_threads; ++threads) {
    std::vector<double> times;
    double cpu_per_wall = 0;
    bool same = true;
    for (int r = 0; r < s.repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      const std::clock_t cpu_start = std::clock();
      auto results = ensemble.integrate(s.t_end, threads);
      const double cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      times.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      if (times.back() <= *std::min_element(times.begin(), times.end()))
        cpu_per_wall = cpu / times.back();
      if (serial.empty()) serial = results;
      same = same && identical(results, serial);
    }
    std::sort(times.begin(), times.end());
    rows.push_back({threads, times.front(), times[times.size() / 2], cpu_per_wall, same});
    std::printf("threads %d: best %.3f s, median %.3f s, speedup %.2f, bit-identical: %s\n",
                threads, rows.back().best, rows.back().median, rows.front().best / rows.back().best,
                same ? "yes" : "NO");
  }
  return rows;
}

void write_report(const Settings& s, const std::vector<Row>& rows) {
  fs::create_directories(s.out / "charts");
  Chart chart{"erkn::Ensemble: speedup against threads (" + std::to_string(s.trajectories) +
                  " trajectories)",
              "threads",
              "speedup (best wall time, 1 thread / T threads)",
              {}};
  erkn::scaling::Series measured{"measured", "#1f77b4", {}, {}},
      ideal{"ideal: min(T, hardware threads)", "#999999", {}, {}, true};
  const double hw = std::thread::hardware_concurrency();
  for (const Row& r : rows) {
    measured.x.push_back(r.threads), measured.y.push_back(rows.front().best / r.best);
    ideal.x.push_back(r.threads), ideal.y.push_back(std::min<double>(r.threads, hw));
  }
  chart.series = {measured, ideal};
  erkn::scaling::write_svg(chart, s.out / "charts" / "ensemble_speedup.svg");
  std::ofstream md(s.out / "ensemble.md");
  md << "# Ensemble speedup\n\nWritten by `erkn-ensemble-speedup` (run by `scripts/main.sh`). "
     << s.trajectories << " trajectories of periodic sine-Gordon (problem 1, N = " << s.N
     << ", each with its own initial velocity), " << s.method << ", h = " << s.h << ", t = 0.."
     << s.t_end << "; wall time of `Ensemble::integrate`, best and median of " << s.repeats
     << " repeats. This machine reports " << hw
     << " hardware threads and is shared with other jobs (load average at the start of this run: "
     << s.load << "), so more threads than that cannot speed up and the times are noisy."
     << (s.autogroup == "1"
             ? " The kernel's autogroup scheduling is on (/proc/sys/kernel/sched_autogroup_enabled "
               "= 1): CPU time is shared equally between sessions, not threads, so while other "
               "sessions keep the cores busy, more threads do not give this process more CPU "
               "time (the CPU time / wall time column) and cannot speed it up."
             : "")
     << "\n\n"
     << "| threads | best wall time [s] | median [s] | speedup (best) | efficiency | "
        "CPU time / wall time | bit-identical to 1 thread |\n|---|---|---|---|---|---|---|\n";
  char line[200];
  for (const Row& r : rows) {
    const double speedup = rows.front().best / r.best;
    std::snprintf(line, sizeof line, "| %d | %.3f | %.3f | %.2f | %.0f %% | %.2f | %s |\n",
                  r.threads, r.best, r.median, speedup, 100 * speedup / r.threads, r.cpu_per_wall,
                  r.identical ? "yes" : "NO");
    md << line;
  }
  md << "\n![speedup](charts/ensemble_speedup.svg)\n";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Settings s = parse(argc, argv);
    const std::vector<Row> rows = measure(s);
    write_report(s, rows);
    for (const Row& r : rows)
      if (!r.identical) return 1;
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "erkn-ensemble-speedup: %s\n", e.what());
    return 2;
  }
}
