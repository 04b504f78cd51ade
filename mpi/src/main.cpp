// erkn-mpi: sine-Gordon on a tensor grid distributed over MPI ranks (FFTW-MPI slabs).
//   mpirun -np N erkn-mpi run [--grid 256x256] [--boundary periodic] [--shift 0]
//                             [--method SERKN2s4] [--h 1e-3] [--steps 20] [--repeats 3]
//   mpirun -np N erkn-mpi scaling --table FILE   appends this rank count's strong- and
//                                                weak-scaling rows to FILE (tab-separated);
//                                                on 1 rank also the serial Integrator's row
//   mpirun -np N erkn-mpi guard-cost [--rounds 5] [the options of run]   the blow-up guard's
//                                                cost: runs with it on and off, alternated
//   mpirun -np 1 erkn-mpi versus --table FILE --methods "M1;M2" [--rounds 5] [the options of
//                                                run]   per method, 1 rank against the serial
//                                                Integrator, alternated: appends their rows
//   erkn-mpi report --table FILE --out FILE.md   the scaling tables and the model beyond them
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "report.hpp"
#include "scene.hpp"

namespace {

using namespace erkn::mpi;

std::map<std::string, std::string> options(int argc, char** argv, int first) {
  std::map<std::string, std::string> o{{"--grid", "256x256"}, {"--boundary", "periodic"},
                                       {"--shift", "0"},      {"--method", "SERKN2s4"},
                                       {"--h", "1e-3"},       {"--steps", "20"},
                                       {"--repeats", "3"},    {"--weak-rows", "64"},
                                       {"--rounds", "5"}};
  for (int i = first; i < argc; i += 2) {
    if (i + 1 >= argc) throw erkn::Error(std::string("option ") + argv[i] + " needs a value");
    o[argv[i]] = argv[i + 1];
  }
  return o;
}

const std::string& required(const std::map<std::string, std::string>& o, const std::string& key) {
  const auto it = o.find(key);
  if (it == o.end()) throw erkn::Error("option " + key + " is required");
  return it->second;
}

// The whole of o[key] as a number, else erkn::Error naming the option.
double number(const std::map<std::string, std::string>& o, const std::string& key) {
  const std::string& text = required(o, key);
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(x))
    throw erkn::Error("option " + key + ": '" + text + "' is not a finite number");
  return x;
}

scene::Settings settings(std::map<std::string, std::string>& o) {
  scene::Settings s;
  s.axes = scene::parse_axes(o["--grid"], o["--boundary"]);
  s.shift = number(o, "--shift");
  s.method = o["--method"];
  s.h = number(o, "--h");
  s.steps = int(number(o, "--steps"));
  s.repeats = int(number(o, "--repeats"));
  if (s.steps < 1 || s.repeats < 1) throw erkn::Error("--steps and --repeats must be >= 1");
  return s;
}

void print(const std::string& kind, const scene::Settings& s, const scene::Timing& t) {
  char transforms[160] = "transforms not counted";  // (the serial Integrator's)
  if (kind.find("serial") == std::string::npos)
    std::snprintf(transforms, sizeof transforms,
                  "%.0f %% in transforms, %.1f transforms per step, all-to-all %.3g MB per step",
                  100 * t.transform_seconds_per_step / t.seconds_per_step, t.transforms_per_step,
                  report::alltoall_bytes(t.d, t.ranks, t.transforms_per_step) / 1e6);
  std::printf(
      "%s: ranks %d, grid %s (d = %ld), %s, h = %g: %.3e s per step (%s), %.1f grad U per step, "
      "energy drift %.2e, sum q = %.15e\n",
      kind.c_str(), t.ranks, scene::describe(s.axes).c_str(), t.d, s.method.c_str(), s.h,
      t.seconds_per_step, transforms, t.gradients_per_step, t.energy_drift, t.sum_q);
}

int scaling(std::map<std::string, std::string>& o, int rank, int ranks) {
  scene::Settings strong = settings(o), weak = strong;
  weak.axes[0].n =
      Eigen::Index(number(o, "--weak-rows")) * ranks;  // fixed rows per rank along axis 0
  weak.axes[0].spacing = strong.axes[0].spacing * double(strong.axes[0].n) / double(weak.axes[0].n);
  const scene::Timing ts = scene::run(MPI_COMM_WORLD, strong),
                      tw = scene::run(MPI_COMM_WORLD, weak);
  if (rank == 0) {
    print("strong", strong, ts), print("weak", weak, tw);
    std::ofstream table(required(o, "--table"), std::ios::app);
    report::append(table, "strong", scene::describe(strong.axes), strong.method, ts);
    report::append(table, "weak", scene::describe(weak.axes), weak.method, tw);
    if (ranks == 1) {  // the serial library on the strong grid: the baseline a user has without MPI
      const scene::Timing serial = scene::run_serial(strong);
      print("serial", strong, serial);
      report::append(table, "serial", scene::describe(strong.axes), strong.method, serial);
    }
    if (!table) throw erkn::Error("cannot write " + required(o, "--table"));
  }
  return 0;
}

// --rounds (>= 1) of an alternated comparison.
int rounds(const std::map<std::string, std::string>& o) {
  const int n = int(number(o, "--rounds"));
  if (n < 1) throw erkn::Error("--rounds must be >= 1");
  return n;
}

// `n` rounds of f(0) and f(1), which of the two goes first alternating from round to round.
template <class F>
void alternate(int n, F&& f) {
  for (int round = 0; round < n; ++round)
    for (int side : {round % 2, 1 - round % 2}) f(side);
}

// The blow-up guard's cost (Options::blowup_guard): `--rounds` rounds of a run with the guard on
// and one with it off, which goes first alternating, in this one process; the best time per step
// of each (of the slowest rank, wall and CPU) and their ratio on / off, and the transforms per
// step of each (its work, free of the machine's noise: a check transforms q once).
int guard_cost(std::map<std::string, std::string>& o, int rank) {
  scene::Settings s = settings(o);
  const int n = rounds(o);
  double wall[2] = {1e300, 1e300}, cpu[2] = {1e300, 1e300}, transforms[2] = {0, 0};
  alternate(n, [&](int guard) {
    s.guard = guard == 1;
    const scene::Timing t = scene::run(MPI_COMM_WORLD, s);
    wall[guard] = std::min(wall[guard], t.seconds_per_step);
    cpu[guard] = std::min(cpu[guard], t.cpu_seconds_per_step);
    transforms[guard] = t.transforms_per_step;
  });
  if (rank == 0)
    std::printf(
        "guard-cost: grid %s, %s, h = %g, %d x %d steps per run, %d rounds: wall %.4e s per step "
        "off, %.4e on, on/off %.4f; CPU %.4e off, %.4e on, on/off %.4f; transforms per step "
        "%.6f off, %.6f on, on/off %.6f\n",
        scene::describe(s.axes).c_str(), s.method.c_str(), s.h, s.repeats, s.steps, n, wall[0],
        wall[1], wall[1] / wall[0], cpu[0], cpu[1], cpu[1] / cpu[0], transforms[0], transforms[1],
        transforms[1] / transforms[0]);
  return 0;
}

// The timing of the median round (by time per step).
scene::Timing median(std::vector<scene::Timing> runs) {
  std::sort(runs.begin(), runs.end(), [](const scene::Timing& a, const scene::Timing& b) {
    return a.seconds_per_step < b.seconds_per_step;
  });
  return runs[runs.size() / 2];
}

// Per method of --methods (separated by ';': names have commas), `--rounds` rounds of the
// distributed run on this one rank and the serial Integrator on the same grid and step, which
// goes first alternating, in this process; the median round of each appended to --table (kinds
// versus-mpi and versus-serial).
int versus(std::map<std::string, std::string>& o, int ranks) {
  if (ranks != 1) throw erkn::Error("versus compares one rank with the serial library: -np 1");
  scene::Settings s = settings(o);
  const int n = rounds(o);
  std::ofstream table(required(o, "--table"), std::ios::app);
  for (const std::string& method : scene::split(required(o, "--methods"), ';')) {
    s.method = method;
    std::vector<scene::Timing> distributed, serial;
    alternate(n, [&](int on_serial) {
      if (on_serial)
        serial.push_back(scene::run_serial(s));
      else
        distributed.push_back(scene::run(MPI_COMM_WORLD, s));
    });
    const scene::Timing d = median(distributed), t = median(serial);
    print("versus-mpi", s, d), print("versus-serial", s, t);
    report::append(table, "versus-mpi", scene::describe(s.axes), method, d);
    report::append(table, "versus-serial", scene::describe(s.axes), method, t);
  }
  if (!table) throw erkn::Error("cannot write " + required(o, "--table"));
  return 0;
}

int dispatch(int argc, char** argv, int rank, int ranks) {
  const std::string command = argc > 1 ? argv[1] : "";
  auto o = options(argc, argv, 2);
  if (command == "run") {
    const scene::Settings s = settings(o);
    const scene::Timing t = scene::run(MPI_COMM_WORLD, s);
    if (rank == 0) print("run", s, t);
    return 0;
  }
  if (command == "scaling") return scaling(o, rank, ranks);
  if (command == "guard-cost") return guard_cost(o, rank);
  if (command == "versus") return versus(o, ranks);
  if (command == "report") {
    if (rank == 0) report::write(required(o, "--table"), required(o, "--out"));
    return 0;
  }
  throw erkn::Error(
      "usage:\n"
      "  mpirun -np N erkn-mpi run [--grid 256x256] [--boundary periodic|dirichlet|neumann[,...]]\n"
      "                            [--shift 0] [--method SERKN2s4] [--h 1e-3] [--steps 20]\n"
      "                            [--repeats 3]\n"
      "  mpirun -np N erkn-mpi scaling --table FILE [the options of run] [--weak-rows 64]\n"
      "  mpirun -np N erkn-mpi guard-cost [the options of run] [--rounds 5]\n"
      "  mpirun -np 1 erkn-mpi versus --table FILE --methods \"M1;M2\" [the options of run]\n"
      "                               [--rounds 5]\n"
      "  erkn-mpi report --table FILE --out FILE.md");
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1, status = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  try {
    status = dispatch(argc, argv, rank, ranks);
  } catch (const std::exception& e) {  // (erkn::Errors are thrown on every rank alike)
    if (rank == 0) std::fprintf(stderr, "%s\n", e.what());
    status = 2;
  }
  MPI_Finalize();
  return status;
}
