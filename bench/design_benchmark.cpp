// The methods erkn's own search designed (a source naming generator/search/) against every other
// method of the registry and the specialist's hand-written loops, CPU to a tolerance.
//
// For every scene of the accuracy benchmark (tolerance_scenes.hpp) and tol: each contender's
// fewest steps n (h = t_end / n) with error <= tol, found by a scan n = ceil(2 * 2^(k/8)) up to
// the first passing n and a bisection down from it to the last failing one. Contenders: every
// registry method in erkn's Integrator (construction + integrate), and every explicit one in the
// specialist's loop (bench/specialist_peer.hpp) on the scenes that have one (P1, P2, P3, SG2D).
// A scan stops once a run costs 3x the cheapest passing run known. The contenders whose scan
// run came within 2x of the cheapest are re-timed at their n in interleaved rounds (setup
// included, thread CPU, median), and per cell the best designed contender is compared with the
// best of all the others: the margin is their CPU ratio - 1.
//
//   erkn_design_benchmark [--methods-file F.json] [--scene KEY] [--tol T]... [--rounds R]
//                         [--markdown FILE]
#include <algorithm>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "integrate_timing.hpp"
#include "scenes.hpp"
#include "tolerance_scenes.hpp"

namespace {

using Scene = bench::ToleranceScene;
bool verbose = false;  // --verbose: every timed contender on stderr

// A method run one way: erkn's Integrator or the specialist's loop, n steps over [0, t_error].
struct Way {
  std::string label;
  bool designed = false;
  std::function<double(long)> error;  // runs n steps, returns the error at t_error
  int gradients = 0;                  // per step (explicit methods; 0: implicit)
};

// Gradients per step of an explicit method: s, or s - 1 when c_1 = 0 and c_s = 1 (the last
// kick of a step merged with the first of the next); 0 for implicit methods.
int gradients(const erkn::Method& m) {
  if (!m.is_explicit()) return 0;
  const int s = m.stages();
  return s > 1 && m.table().c[0] == 0 && m.table().c[s - 1] == 1 ? s - 1 : s;
}

bool designed(const erkn::Method& m) {
  return std::string(m.table().reference).find("generator/search/") != std::string::npos;
}

Way erkn_way(const Scene& s, const erkn::Method& m) {
  return {std::string(m.name()), designed(m),
          [&s, &m](long n) { return bench::fixed_run(s, m, s.problem.t_error / double(n)).error; },
          gradients(m)};
}

template <class Basis, class Gradient>
Way peer_way(const Scene& s, const erkn::Method& m, std::shared_ptr<Basis> basis, Gradient g) {
  return {std::string(m.name()) + " (specialist)", designed(m),
          [&s, &m, basis, g](long n) {
            bench::specialist::Peer run(m.table().c, m.table().d, m.stages(),
                                        s.problem.t_error / double(n), *basis, g, s.problem.q0,
                                        s.problem.p0);
            run.run(n);
            Eigen::VectorXd q, p;
            run.state(q, p);
            const double e = (q - s.reference).lpNorm<Eigen::Infinity>();
            return std::isfinite(e) ? e : bench::kInf;
          },
          gradients(m)};
}

template <class Basis, class Gradient>
void add_peers(std::vector<Way>& ways, const Scene& s, std::shared_ptr<Basis> basis, Gradient g) {
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed())  // (grad U kicks)
      ways.push_back(peer_way(s, m, basis, g));
}

// Every registry method in erkn, highest order first, then the specialist's loops.
std::vector<Way> ways_of(const Scene& s) {
  std::vector<const erkn::Method*> methods;
  for (const erkn::Method& m : erkn::Method::all()) methods.push_back(&m);
  std::stable_sort(methods.begin(), methods.end(),
                   [](auto* a, auto* b) { return a->order() > b->order(); });
  std::vector<Way> ways;
  for (const erkn::Method* m : methods) ways.push_back(erkn_way(s, *m));
  const std::string& key = s.problem.key;
  if (key == "P2")
    add_peers(ways, s,
              std::make_shared<bench::specialist::IdentityBasis<1>>(
                  bench::identity_basis<1>(s.problem.M, 1)),
              bench::DuffingGradient{});
  else if (key == "P3")
    add_peers(ways, s,
              std::make_shared<bench::specialist::IdentityBasis<2>>(
                  bench::identity_basis<2>(s.problem.M, 2)),
              bench::StellarGradient{});
  else if (key == "P1" || key == "SG2D")
    add_peers(ways, s,
              std::make_shared<bench::specialist::FourierBasis>(bench::fourier_basis(s.problem.M)),
              bench::SineGordonGradient{});
  return ways;
}

struct Fewest {
  long n = 0;      // 0: not reached within the budget
  double cpu = 0;  // one run at n (repeated for at least 0.2 ms)
};

// CPU seconds of one run of n steps, repeated until the sample lasts 0.2 ms (the thread clock
// costs microseconds per read on this VM: single runs of P2, P3 are a few microseconds).
double cpu_of(const Way& w, long n) {
  for (long reps = 1;; reps *= 4) {
    const double t0 = bench::thread_seconds();
    for (long r = 0; r < reps; ++r) w.error(n);
    const double t = bench::thread_seconds() - t0;
    if (t >= 2e-4) return t / double(reps);
  }
}

// The fewest steps reaching tol; gives up when a run costs more than `budget` seconds (and
// 50 us: cheaper runs are not worth pruning on a noisy clock).
Fewest fewest_steps(const Way& w, double tol, double budget) {
  long fail = 0;
  for (int k = 0;; ++k) {
    const long n = long(std::ceil(2 * std::pow(2.0, k / 8.0)));
    if (n > 4000000) return {};
    const double t0 = bench::thread_seconds();
    const double e = w.error(n);
    const double cpu = bench::thread_seconds() - t0;
    if (e <= tol) {
      long lo = fail, hi = n;
      while (hi - lo > 1) {  // error <= tol at hi, not at lo
        const long mid = (lo + hi) / 2;
        (w.error(mid) <= tol ? hi : lo) = mid;
      }
      return {hi, cpu_of(w, hi)};
    }
    if (std::isfinite(e)) fail = n;
    if (cpu > budget && cpu > 5e-5) return {};
  }
}

struct Result {
  std::string label;
  bool designed = false;
  long n = 0;
  long evaluations = 0;      // gradients over the run (0: implicit)
  double cpu = bench::kInf;  // re-timed median
};

// The contenders within 2x of the cheapest scan run, re-timed interleaved.
std::vector<Result> timed(const std::vector<Way>& ways, const std::vector<Fewest>& fewest,
                          int rounds) {
  double cheapest = bench::kInf;
  for (const Fewest& f : fewest)
    if (f.n) cheapest = std::min(cheapest, f.cpu);
  std::vector<Result> out;
  std::vector<std::function<void()>> runs;
  for (size_t i = 0; i < ways.size(); ++i)
    if (fewest[i].n && fewest[i].cpu <= 2 * cheapest) {
      out.push_back(
          {ways[i].label, ways[i].designed, fewest[i].n, fewest[i].n * ways[i].gradients});
      runs.push_back([w = &ways[i], n = fewest[i].n] { w->error(n); });
    }
  if (runs.empty()) return out;
  const auto seconds = bench::time_rounds(runs, {rounds, 2e-3});
  for (size_t i = 0; i < out.size(); ++i) out[i].cpu = bench::median(seconds[i]);
  return out;
}

struct Cell {
  std::string scene;
  double tol = 0;
  Result mine, other;  // the best designed contender, the best of the others
  size_t contenders = 0, timed = 0;
};

Cell cell(const Scene& s, const std::vector<Way>& ways, double tol, int rounds) {
  std::vector<Fewest> fewest;
  double best = bench::kInf;
  for (const Way& w : ways) {
    fewest.push_back(fewest_steps(w, tol, 3 * best));
    if (fewest.back().n) best = std::min(best, fewest.back().cpu);
  }
  Cell c{s.problem.key, tol};
  c.contenders = ways.size();
  for (const Result& r : timed(ways, fewest, rounds)) {
    ++c.timed;
    if (verbose) std::cerr << "  " << r.label << " n = " << r.n << ": " << 1e6 * r.cpu << " us\n";
    Result& slot = r.designed ? c.mine : c.other;
    if (r.cpu < slot.cpu) slot = r;
  }
  return c;
}

std::string fixed(double x, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::string row(const Cell& c) {
  auto who = [](const Result& r) {
    return std::isfinite(r.cpu) ? r.label + " | " + std::to_string(r.n) + " | " +
                                      std::to_string(r.evaluations) + " | " + fixed(1e6 * r.cpu, 2)
                                : std::string("(not within 2x) | | | ");
  };
  const double margin = c.other.cpu / c.mine.cpu - 1;
  return "| " + c.scene + " | " + bench::sci(c.tol, 0) + " | " + who(c.mine) + " | " +
         who(c.other) + " | " + (std::isfinite(c.mine.cpu) ? fixed(100 * margin, 1) + " %" : "") +
         " | " + (margin >= 0.10 ? "**met**" : "not met") + " |\n";
}

struct Config {
  std::string markdown, scene, methods_file;
  std::vector<double> tols;
  int rounds = 7;
};

Config parse(int argc, char** argv) {
  Config cfg;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--markdown")
      cfg.markdown = v;
    else if (a == "--scene")
      cfg.scene = v;
    else if (a == "--methods-file")
      cfg.methods_file = v;
    else if (a == "--tol")
      cfg.tols.push_back(std::stod(v));
    else if (a == "--rounds")
      cfg.rounds = std::stoi(v);
    else if (a == "--verbose")
      verbose = v == "1";
    else
      throw std::invalid_argument("unknown argument " + a);
  }
  if (argc % 2 == 0) throw std::invalid_argument("an option without its value");
  if (cfg.tols.empty()) cfg.tols = {1e-4, 1e-6, 1e-8, 1e-10};
  return cfg;
}

std::string header() {
  return "| scene | tol | designed | n | gradients | CPU us | best other | n | gradients | CPU us "
         "| margin | >= 10 % |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

}  // namespace

int main(int argc, char** argv) try {
  const Config cfg = parse(argc, argv);
  if (!cfg.methods_file.empty()) erkn::Method::load(cfg.methods_file);
  std::string table = header();
  int met = 0, cells = 0;
  for (erkn::problems::Problem& p : bench::tolerance_problems(cfg.scene)) {
    const Scene s = bench::tolerance_scene(std::move(p));
    const std::vector<Way> ways = ways_of(s);
    for (double tol : cfg.tols) {
      const Cell c = cell(s, ways, tol, cfg.rounds);
      table += row(c);
      std::cerr << row(c);
      ++cells, met += c.other.cpu >= 1.10 * c.mine.cpu;
    }
  }
  const std::string md =
      "<!-- Written by bench/design_benchmark.cpp (erkn_design_benchmark --markdown). Do not "
      "edit. -->\n\nPer cell: the designed method (source naming generator/search/) and the "
      "best other contender (every other registry method in erkn's Integrator, every explicit "
      "one in the specialist's loop where the scene has one), each at its fewest steps n to "
      "the tolerance, re-timed in " +
      std::to_string(cfg.rounds) +
      " interleaved rounds (setup included, thread CPU, median; contenders within 2x of the "
      "cheapest scan run). Gradients: evaluations of grad U over the run (explicit methods). "
      "Margin: CPU of the best other / CPU of the designed - 1.\n\n" +
      table + "\nMargin >= 10 % in " + std::to_string(met) + " of " + std::to_string(cells) +
      " cells.\n";
  if (cfg.markdown.empty())
    std::cout << md;
  else
    std::ofstream(cfg.markdown) << md;
  return 0;
} catch (const std::exception& e) {
  std::cerr << "erkn_design_benchmark: " << e.what() << "\n";
  return 2;
}
