#include "report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace erkn::mpi::report {
namespace {

struct Row {
  std::string kind, grid, method;
  scene::Timing t;
};

using Rows = std::map<std::pair<std::string, int>, Row>;            // (kind, ranks)
using Versus = std::map<std::pair<std::string, std::string>, Row>;  // (method, kind)

// The scaling rows and the rows of `erkn-mpi versus` (kinds versus-mpi, versus-serial).
struct Table {
  Rows rows;
  Versus versus;
};

Table read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read " + path);
  Table table;
  for (std::string line; std::getline(in, line);) {
    std::istringstream f(line);
    Row r;
    scene::Timing& t = r.t;
    if (!(f >> r.kind >> r.grid >> r.method >> t.ranks >> t.d >> t.seconds_per_step >>
          t.transform_seconds_per_step >> t.transforms_per_step >> t.gradients_per_step >>
          t.energy_drift >> t.sum_q >> t.norm_q >> t.cpu_seconds_per_step))
      continue;
    f >> t.load;  // (not in the tables of older versions)
    if (r.kind.rfind("versus-", 0) == 0)
      table.versus[{r.method, r.kind}] = r;
    else
      table.rows[{r.kind, t.ranks}] = r;
  }
  return table;
}

std::string format(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

// One row of a measured table; versus: the serial Integrator's time per step (strong scaling),
// else 0 (no such column); the serial row has no transforms counted.
void measured_row(std::ostream& md, const Row& r, const Row* one, double versus) {
  const scene::Timing& t = r.t;
  const bool serial = r.kind == "serial", strong = r.kind != "weak";
  md << "| " << (serial ? "serial Integrator" : std::to_string(t.ranks)) << " | " << r.grid << " | "
     << t.d << " | " << t.d / t.ranks << " | " << format("%.2f", 1e3 * t.seconds_per_step) << " | "
     << (one && !serial ? format("%.2f", one->t.seconds_per_step / t.seconds_per_step) : "-")
     << " | ";
  if (versus > 0) md << format("%.2f", versus / t.seconds_per_step) << " | ";
  md << format("%.2f", t.cpu_seconds_per_step / t.seconds_per_step) << " | "
     << (serial ? "-" : format("%.0f %%", 100 * t.transform_seconds_per_step / t.seconds_per_step))
     << " | " << (serial ? "-" : format("%.1f", t.transforms_per_step)) << " | "
     << (serial ? "-"
                : format("%.2f", alltoall_bytes(double(t.d), t.ranks, t.transforms_per_step) / 1e6))
     << " | " << format("%.1e", t.energy_drift) << " | "
     << (one && strong ? format("%.1e", std::abs(t.sum_q - one->t.sum_q) / std::abs(one->t.sum_q))
                       : "-")
     << " |\n";
}

// The rows of one kind ("strong" with the serial Integrator's row first, "weak").
void measured_table(std::ostream& md, const Rows& rows, const std::string& kind) {
  const auto one = rows.find({kind, 1});
  const Row* base = one != rows.end() ? &one->second : nullptr;
  const auto serial = kind == "strong" ? rows.find({"serial", 1}) : rows.end();
  const double versus = serial != rows.end() ? serial->second.t.seconds_per_step : 0;
  md << "| ranks | grid | d | d per rank | time per step [ms] | "
     << (kind == "strong" ? "speedup" : "time(1)/time(P)") << " | "
     << (versus > 0 ? "serial Integrator's time / time | " : "")
     << "CPU time / wall time | in transforms | transforms per step | all-to-all per step [MB] | "
        "relative energy drift | sum of q, relative to 1 rank |\n"
        "|---|---|---|---|---|---|"
     << (versus > 0 ? "---|" : "") << "---|---|---|---|---|---|\n";
  if (versus > 0) measured_row(md, serial->second, base, versus);
  for (const auto& [key, r] : rows)
    if (key.first == kind) measured_row(md, r, base, versus);
}

// The rows of `erkn-mpi versus`: per method, the serial Integrator and 1 rank, side by side.
void versus_table(std::ostream& md, const Versus& versus) {
  md << "\n## One rank against the serial library, per method\n\n"
        "Written from `mpirun -np 1 erkn-mpi versus --methods ...` (run by `scripts/main.sh`): for "
        "each method, rounds of the distributed run on 1 rank and the serial Integrator on the "
        "same grid and step, which of the two goes first alternating, in one process; each "
        "round's time per step is the best of its repeats, and the table has the median round "
        "of each (both include loading the physical state once per block: the distributed "
        "integrate() loads it, the serial block calls q()). Explicit methods (every abar_ii = 0) "
        "run the library's explicit stepper on both sides, implicit ones its stage solver. The "
        "load is the machine's 1-minute load average after the distributed run.\n\n"
        "| method | grid | serial Integrator [ms per step] | 1 rank [ms per step] | serial "
        "Integrator's time / time | transforms per step | grad U per step (serial, 1 rank) | sum "
        "of q, 1 rank vs serial | load |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, distributed] : versus) {
    if (key.second != "versus-mpi") continue;
    const auto serial = versus.find({key.first, "versus-serial"});
    if (serial == versus.end()) continue;
    const scene::Timing &t = distributed.t, &s = serial->second.t;
    md << "| " << key.first << " | " << distributed.grid << " | "
       << format("%.2f", 1e3 * s.seconds_per_step) << " | "
       << format("%.2f", 1e3 * t.seconds_per_step) << " | "
       << format("%.2f", s.seconds_per_step / t.seconds_per_step) << " | "
       << format("%.1f", t.transforms_per_step) << " | " << format("%.1f", s.gradients_per_step)
       << ", " << format("%.1f", t.gradients_per_step) << " | "
       << format("%.1e", std::abs(t.sum_q - s.sum_q) / std::abs(s.sum_q)) << " | "
       << format("%.1f", t.load) << " |\n";
  }
}

// Time per step predicted for d unknowns (grid side n) on P ranks: the measured local costs per
// unknown, plus per transform an all-to-all with latency alpha per message and bandwidth beta.
void model_table(std::ostream& md, const Row& base) {
  const scene::Timing& t = base.t;
  const double nT = t.transforms_per_step, d1 = double(t.d);
  // CPU time (what the process got of this shared machine), split like the wall time.
  const double share = t.transform_seconds_per_step / t.seconds_per_step;
  const double local = t.cpu_seconds_per_step * (1 - share) / d1;
  const double fft = t.cpu_seconds_per_step * share / (nT * d1 * std::log2(d1));
  const double alpha = 2e-6, beta = 5e9;
  md << "Measured on 1 rank (" << base.grid << ", " << base.method << "): " << format("%.1f", nT)
     << " transforms per step; from its CPU time (its wall time also counts the other jobs on "
        "this machine), split between the transforms and the rest as the wall time: "
     << format("%.2f ns", 1e9 * local) << " per unknown per step outside the transforms, "
     << format("%.3f ns", 1e9 * fft) << " per unknown per log2(d) per transform. Assumed network "
     << "(typical of an InfiniBand cluster, an assumption, not a measurement): latency alpha = "
     << alpha * 1e6 << " us per message, bandwidth beta = " << beta / 1e9
     << " GB/s per rank. Model per step:\n\n"
     << "    T(d, P) = d/P (local + nT fft log2 d) + nT [ (P-1) alpha + 8 d (P-1) / (P^2 beta) "
        "]\n\n"
     << "Each transform is one all-to-all in which every rank sends 8 d (P-1)/P^2 bytes in P-1 "
        "messages (total 8 d (P-1)/P bytes): the volume per rank falls like 1/P, the number of "
        "messages grows like P, so latency dominates once d/P is small. Slabs need P <= the "
        "smaller of the first two axes; beyond that a pencil decomposition (not FFTW-MPI) is "
        "needed.\n\n"
        "| grid | d | P | all-to-all per step, all ranks [MB] | per rank [MB] | messages per rank "
        "| predicted time per step | all-to-all share | parallel efficiency |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [grid, side, dims] :
       {std::tuple{"1024^2", 1024.0, 2}, std::tuple{"4096^2", 4096.0, 2},
        std::tuple{"256^3", 256.0, 3}, std::tuple{"1024^3", 1024.0, 3}}) {
    const double d = std::pow(side, dims);
    const double T1 = d * (local + nT * fft * std::log2(d));
    for (int P : {1, 16, 64, 256, 1024, 4096}) {
      if (P > side) {
        md << "| " << grid << " | " << format("%.3g", d) << " | " << P
           << " | | | | beyond the slab limit (P > " << side << ") | | |\n";
        continue;
      }
      const double comm = nT * ((P - 1) * alpha + 8 * d * (P - 1) / (double(P) * P * beta));
      const double T = T1 / P + comm;
      const double volume = alltoall_bytes(d, P, nT);
      md << "| " << grid << " | " << format("%.3g", d) << " | " << P << " | "
         << format("%.4g", volume / 1e6) << " | " << format("%.4g", volume / P / 1e6) << " | "
         << format("%.0f", nT * (P - 1)) << " | "
         << format(T < 1 ? "%.3g ms" : "%.3g s", T < 1 ? 1e3 * T : T) << " | "
         << format("%.0f %%", 100 * comm / T) << " | " << format("%.0f %%", 100 * T1 / (P * T))
         << " |\n";
    }
  }
}

}  // namespace

void append(std::ostream& table, const std::string& kind, const std::string& grid,
            const std::string& method, const scene::Timing& t) {
  table.precision(17);
  table << kind << '\t' << grid << '\t' << method << '\t' << t.ranks << '\t' << t.d << '\t'
        << t.seconds_per_step << '\t' << t.transform_seconds_per_step << '\t'
        << t.transforms_per_step << '\t' << t.gradients_per_step << '\t' << t.energy_drift << '\t'
        << t.sum_q << '\t' << t.norm_q << '\t' << t.cpu_seconds_per_step << '\t' << t.load << '\n';
}

void write(const std::string& table_file, const std::string& markdown) {
  const Table table = read(table_file);
  const Rows& rows = table.rows;
  std::ofstream md(markdown);
  md << "# Beyond one machine: MPI scaling\n\n"
        "Written by `erkn-mpi report` from the rows `mpirun -np P erkn-mpi scaling` appended for "
        "P = 1, 2, 4 (run by `scripts/main.sh`). Sine-Gordon on a periodic grid over [-1, 1]^2, "
        "distributed in slabs along the first axis; times are the best of the repeats, of the "
        "slowest rank. This machine has 2 cores shared with other jobs: 4 ranks are "
        "oversubscribed (`--oversubscribe`), so the 4-rank rows show the cost of the exchange "
        "rather than a speedup. CPU time / wall time is the share of a core the busiest rank got: "
        "well below 1, the run waited for the machine (in a collective call a rank waits for the "
        "slowest), not for its own work.";
  std::ifstream autogroup("/proc/sys/kernel/sched_autogroup_enabled");
  int enabled = 0;
  if (autogroup >> enabled && enabled == 1)
    md << " The kernel's autogroup scheduling is on (/proc/sys/kernel/sched_autogroup_enabled = "
          "1): CPU time is shared equally between sessions, and the ranks of one mpirun are one "
          "session, so while other sessions keep the cores busy more ranks share the same CPU "
          "time and every all-to-all waits for descheduled ranks.";
  md << "\n\n## Strong scaling (fixed grid)\n\n";
  if (rows.count({"serial", 1}))
    md << "The first row is the serial library (erkn::Integrator in one process, no MPI: "
          "`Integrator::step(n)`, then `q()`: the state loaded once per block, as the "
          "distributed `integrate()` loads it) on the same grid, method and step: what a user "
          "without MPI runs. Its column \"serial Integrator's time / time\" is the speedup over it "
          "(below 1: "
          "the distributed run is slower).\n\n";
  measured_table(md, rows, "strong");
  md << "\n## Weak scaling (fixed rows per rank)\n\n";
  measured_table(md, rows, "weak");
  if (!table.versus.empty()) versus_table(md, table.versus);
  md << "\n## Beyond this machine: the model\n\n";
  const auto base = rows.find({"strong", 1});
  if (base == rows.end())
    md << "(no 1-rank strong-scaling row in the table: no model)\n";
  else
    model_table(md, base->second);
  if (!md) throw Error("cannot write " + markdown);
}

}  // namespace erkn::mpi::report
