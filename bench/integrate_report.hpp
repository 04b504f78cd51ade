// erkn_integrate_benchmark's output: a text table, a csv of every cell's ratios, and the
// Markdown of docs/benchmarks.md with met / NOT met per cell, the cells-met counts and, given a
// previous run's csv, the run-to-run spread per cell.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "integrate_cells.hpp"

namespace bench {

inline constexpr double kPlainTarget = 1.0, kDefaultTarget = 1.05, kImplicitTarget = 1.2;
inline constexpr double kSpreadTarget = 0.10;

inline const char* verdict(double ratio, double target) {
  return ratio <= target ? "met" : "NOT met";
}

/// What bounds an implicit cell: met (erkn's ratio <= kImplicitTarget); where not, the method
/// through the callback (the specialist's floor loop through the same System::gradient is itself
/// above the target) or erkn (it is not); unknown where the floor was not timed or disagreed.
inline const char* implicit_bound(const ImplicitCell& c) {
  if (c.ratio <= kImplicitTarget) return "met";
  if (c.floor.status == FloorColumns::Status::not_timed) return "floor not timed";
  if (c.floor.status == FloorColumns::Status::disagrees) return "floor disagrees";
  return c.floor.floor > kImplicitTarget ? "the method through the callback" : "erkn";
}

/// The implicit cells by bound: not met, and of those bounded by the method through the callback,
/// by erkn, unknown.
struct ImplicitBounds {
  int cells = 0, met = 0, missed = 0, by_method = 0, by_erkn = 0, unknown = 0;
  explicit ImplicitBounds(const std::vector<ImplicitCell>& all) {
    for (const ImplicitCell& c : all) {
      const std::string bound = implicit_bound(c);
      ++cells, met += bound == "met", missed += bound != "met";
      by_method += bound == "the method through the callback", by_erkn += bound == "erkn";
    }
    unknown = missed - by_method - by_erkn;
  }
};

/// "two states: fast N, slow N ns per grad U (above N: slow)" or "one state: N ns per grad U".
inline std::string describe(const StateSplit& s) {
  char buf[160];
  if (s.two_states)
    std::snprintf(
        buf, sizeof buf,
        "two states: fast %.2f, slow %.2f ns per grad U of the explicit path (above %.2f: slow)",
        s.fast, s.slow, s.threshold);
  else
    std::snprintf(buf, sizeof buf, "one state: %.2f ns per grad U of the explicit path", s.fast);
  return buf;
}

inline void print_text(const Results& r, const Config&, FILE* f) {
  std::fprintf(f, "host state probe: %s\n", describe(r.host).c_str());
  std::fprintf(f, "%-22s %-9s %5s %9s | %6s %6s %6s | %5s\n", "scene", "method", "steps", "peer ms",
               "plain", "dflt", "output", "slow");
  for (const Cell& c : r.cells) {
    std::fprintf(f, "%-22s %-9s %5ld %9.3f | %6.3f %6.3f %6.3f | %zu/%zu", c.scene.c_str(),
                 c.method.c_str(), c.steps, c.peer_ms, c.plain, c.deflt, c.output,
                 c.states.slow_rounds(), c.states.slow.size());
    if (!std::isnan(c.callback_peer))  // (peer through the callback / inlined; erkn / it)
      std::fprintf(f, " | callback peer %6.3f, erkn / it %6.3f %6.3f", c.callback_peer, c.plain_cb,
                   c.deflt_cb);
    std::fprintf(f, "\n");
  }
  for (const ImplicitCell& c : r.implicit_cells)
    std::fprintf(f,
                 "%-22s %-14s %8.4f us/grad (explicit %8.4f) ratio %6.3f, fast rounds %6.3f, "
                 "slow rounds %6.3f (%zu/%zu) | floor %6.3f, erkn / floor %6.3f, inlined %6.3f, "
                 "diff %.1e: %s\n",
                 c.scene.c_str(), c.method.c_str(), c.us_per_grad, c.explicit_us_per_grad, c.ratio,
                 c.ratio_fast, c.ratio_slow, c.states.slow_rounds(), c.states.slow.size(),
                 c.floor.floor, c.floor.erkn_floor, c.floor.inlined, c.floor.diff,
                 implicit_bound(c));
}

/// The probe's readings of a cell's rounds, space-separated (the csv's last field).
inline std::string readings(const RoundStates& s) {
  std::ostringstream out;
  out.precision(4);
  for (size_t r = 0; r < s.probe.size(); ++r) out << (r ? " " : "") << s.probe[r];
  return out.str();
}

/// A csv field (RFC 4180): quoted, its quotes doubled, when it holds a comma or a quote (method
/// names such as SD9(10,6,4) do).
inline std::string csv_field(const std::string& x) {
  if (x.find_first_of(",\"") == std::string::npos) return x;
  std::string out = "\"";
  for (char c : x) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + '"';
}

/// The fields of a csv line written with csv_field, unquoted.
inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += c, ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

/// One line per ratio: kind,scene,method,value,probe (kind: plain, default, output, implicit; rows
/// through System::gradient also callback_peer, plain_vs_callback_peer, default_vs_callback_peer;
/// implicit cells with a floor also implicit_floor, implicit_vs_floor, implicit_floor_inlined;
/// probe: the host state probe's reading in each of the cell's rounds, ns per grad U).
inline void write_csv(const Results& r, const std::string& path) {
  std::ofstream f(path);
  f << "kind,scene,method,ratio,probe_ns_per_round\n";
  auto row = [&f](const char* kind, const std::string& scene, const std::string& method,
                  double ratio, const RoundStates& s) {
    f << kind << ',' << csv_field(scene) << ',' << csv_field(method) << ',' << ratio << ','
      << readings(s) << '\n';
  };
  for (const Cell& c : r.cells) {
    row("plain", c.scene, c.method, c.plain, c.states);
    row("default", c.scene, c.method, c.deflt, c.states);
    row("output", c.scene, c.method, c.output, c.states);
    if (std::isnan(c.callback_peer)) continue;
    row("callback_peer", c.scene, c.method, c.callback_peer, c.states);
    row("plain_vs_callback_peer", c.scene, c.method, c.plain_cb, c.states);
    row("default_vs_callback_peer", c.scene, c.method, c.deflt_cb, c.states);
  }
  for (const ImplicitCell& c : r.implicit_cells) {
    row("implicit", c.scene, c.method, c.ratio, c.states);
    if (c.floor.status != FloorColumns::Status::timed) continue;
    row("implicit_floor", c.scene, c.method, c.floor.floor, c.states);
    row("implicit_vs_floor", c.scene, c.method, c.floor.erkn_floor, c.states);
    row("implicit_floor_inlined", c.scene, c.method, c.floor.inlined, c.states);
  }
}

/// A ratio of a csv and the probe's readings in its rounds (none in a csv from before the probe).
struct CsvRatio {
  double ratio = NAN;
  std::vector<double> probe;
};

/// kind,scene,method (unquoted) -> ratio and readings from a csv written by write_csv (empty if
/// there is none; a csv without the probe column, from before it, gives ratios without readings).
inline std::map<std::string, CsvRatio> read_csv(const std::string& path) {
  std::map<std::string, CsvRatio> out;
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  const size_t n = line.find(",probe") != std::string::npos ? 5 : 4;
  while (std::getline(f, line)) {
    const std::vector<std::string> x = csv_fields(line);
    if (x.size() != n)
      throw std::runtime_error(path + ": not a row of " + std::to_string(n) +
                               " fields (kind,scene,method,ratio...): " + line);
    CsvRatio value;
    value.ratio = std::stod(x[3]);
    if (n == 5) {
      std::istringstream list(x[4]);
      for (double r; list >> r;) value.probe.push_back(r);
    }
    out[x[0] + ',' + x[1] + ',' + x[2]] = value;
  }
  return out;
}

}  // namespace bench
