// erkn_integrate_benchmark's output: a text table, a csv of every cell's ratios, and the
// Markdown of docs/benchmarks.md with met / NOT met per cell, the cells-met counts and, given a
// previous run's csv, the run-to-run spread per cell.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include "integrate_cells.hpp"

namespace bench {

inline constexpr double kPlainTarget = 1.0, kDefaultTarget = 1.05, kImplicitTarget = 1.2;
inline constexpr double kSpreadTarget = 0.10;

inline const char* verdict(double ratio, double target) {
  return ratio <= target ? "met" : "NOT met";
}

inline void print_text(const Results& r, const Config&, FILE* f) {
  std::fprintf(f, "%-22s %-9s %5s %9s | %6s %6s %6s\n", "scene", "method", "steps", "peer ms",
               "plain", "dflt", "output");
  for (const Cell& c : r.cells) {
    std::fprintf(f, "%-22s %-9s %5ld %9.3f | %6.3f %6.3f %6.3f", c.scene.c_str(), c.method.c_str(),
                 c.steps, c.peer_ms, c.plain, c.deflt, c.output);
    if (!std::isnan(c.callback_peer))  // (peer through the callback / inlined; erkn / it)
      std::fprintf(f, " | callback peer %6.3f, erkn / it %6.3f %6.3f", c.callback_peer, c.plain_cb,
                   c.deflt_cb);
    std::fprintf(f, "\n");
  }
  for (const ImplicitCell& c : r.implicit_cells)
    std::fprintf(f, "%-22s %-14s %8.4f us/grad (explicit %8.4f) ratio %6.3f\n", c.scene.c_str(),
                 c.method.c_str(), c.us_per_grad, c.explicit_us_per_grad, c.ratio);
}

/// One line per ratio: kind,scene,method,value (kind: plain, default, output, implicit; rows
/// through System::gradient also callback_peer, plain_vs_callback_peer, default_vs_callback_peer).
inline void write_csv(const Results& r, const std::string& path) {
  std::ofstream f(path);
  f << "kind,scene,method,ratio\n";
  for (const Cell& c : r.cells) {
    f << "plain," << c.scene << ',' << c.method << ',' << c.plain << '\n';
    f << "default," << c.scene << ',' << c.method << ',' << c.deflt << '\n';
    f << "output," << c.scene << ',' << c.method << ',' << c.output << '\n';
    if (std::isnan(c.callback_peer)) continue;
    f << "callback_peer," << c.scene << ',' << c.method << ',' << c.callback_peer << '\n';
    f << "plain_vs_callback_peer," << c.scene << ',' << c.method << ',' << c.plain_cb << '\n';
    f << "default_vs_callback_peer," << c.scene << ',' << c.method << ',' << c.deflt_cb << '\n';
  }
  for (const ImplicitCell& c : r.implicit_cells)
    f << "implicit," << c.scene << ',' << c.method << ',' << c.ratio << '\n';
}

/// kind,scene,method -> ratio from a csv written by write_csv (empty if there is none).
inline std::map<std::string, double> read_csv(const std::string& path) {
  std::map<std::string, double> out;
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  while (std::getline(f, line)) {
    const size_t comma = line.rfind(',');
    if (comma != std::string::npos) out[line.substr(0, comma)] = std::stod(line.substr(comma + 1));
  }
  return out;
}

}  // namespace bench
