// erkn_advisor_sweep [--steps N] [--points K] [--offset X] [--trial T] [--threads T] [--csv FILE]
// [OUT.md]: the step-size
// advisor's false-alarm and miss rates (docs/advisor.md is this program's output). For each scene
// (FPU, sine-Gordon P1, a 1-D (n = 15) and a 2-D (4^2) Dirichlet wave grid with a cubic force:
// the advisor's logic is the same as at n = 255, and the implicit methods' dense Newton fallback,
// which large h needs on every step, stays affordable) and every method of the registry (ERKN,
// explicit splittings and the RKN limits: the advisor covers them all), at
// h omega = 4 pi (k - X) / K, k = 1..K (omega = sqrt of M's largest eigenvalue; X in [0, 1): a
// training sweep and a measured one share no step size):
//   verdict   advise_step_size(method, system, h, q0, p0) with AdvisorOptions::steps = N flags h
//             (StepSizeAdvice::safe() is false): what Options::check_stability refuses and `erkn
//             advise --problem` reports (Hessian range and mode energies at the start, then the
//             trial run: its first --trial steps, default AdvisorOptions::trial_steps, extended
//             to AdvisorOptions::extended_trial_steps where ambiguous). For
//             comparison, the linear model alone
//             (AdvisorOptions::trial_steps = 0: every finding flags h) is scored too.
//   criterion the relative energy error E = max |H_n - H_0| / |H_0| over N = 1e5 steps of h
//             (sampled every step up to 2^14 steps, then every 50; blow-up guard off) against 0.5,
//             docs/stability-advisor.md's
//             "runs clean" bound (twice the guard's limit). A run BLOWS UP when E >= 0.5 (it stops
//             there: the rest cannot undo that) or when a step throws an erkn::Error (a non-finite
//             state, or a stage solver that fails: the method cannot run at that h); else it is
//             BOUNDED.
// A false alarm is a flagged h whose run is bounded, a miss an unflagged h whose run blows up;
// the false-alarm rate is false alarms / bounded runs, the miss rate misses / blown-up runs.
// Step sizes the integrator refuses at construction (h^2 lambda on a pole) are counted apart.
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "erkn/erkn.hpp"
#include "erkn/problems.hpp"

namespace {

using namespace erkn;
using std::numbers::pi;

constexpr double kBlowUp = 0.5;    // the criterion on the relative energy error
constexpr long kSampleEvery = 50;  // energy samples, in steps
// The sweep the trial's constants were chosen on: h omega = 4 pi (k - kTrainingOffset) / 16.
constexpr double kTrainingOffset = 0.5;
// The error curve kept for the CSV (for choosing the trial's constants on a training sweep): the
// largest error over the first 2^k steps, k < kCurve, sampled every step up to 2^kDense steps.
constexpr int kCurve = 18, kDense = 14;

struct Scene {
  std::string name;
  System system;
  Eigen::VectorXd q0, p0;
  double omega = 0;  // sqrt of M's largest eigenvalue
};

Scene scene(std::string name, System system, Eigen::VectorXd q0, Eigen::VectorXd p0) {
  const double omega = std::sqrt(system.M.eigenvalues().maxCoeff());
  return {std::move(name), std::move(system), std::move(q0), std::move(p0), omega};
}

Scene from_library(const problems::Problem& p, std::string name) {
  return scene(std::move(name), problems::system(p), p.q0, p.p0);
}

// u_tt = Lap u - u^3 on (0, 1)^k, Dirichlet, n interior points per axis (k = 1, 2),
// u0 = prod sin(pi x_a), u_t(0) = 0.
Scene wave_grid(int n, int k) {
  const double dx = 1.0 / (n + 1);
  const Eigen::Index d = k == 1 ? n : n * n;
  // (The grid's matrix, held dense: at d <= 25 every FFTW r2r call allocates its buffers, and
  // the implicit methods' Newton fallback builds each Jacobian from d such calls.)
  const Stiffness grid =
      Stiffness::grid(std::vector<GridAxis>(k, {n, dx, GridAxis::Boundary::dirichlet}));
  const System s =
      problems::system(Stiffness::dense(grid.to_dense(d)), problems::quartic_potential(1));
  Eigen::VectorXd q0(d);
  for (Eigen::Index i = 0; i < d; ++i)  // (row-major: i = i0 n + i1)
    q0[i] = std::sin(pi * (i % n + 1) * dx) * (k == 1 ? 1 : std::sin(pi * (i / n + 1) * dx));
  const std::string size = k == 1 ? std::to_string(n) : std::to_string(n) + "^2";
  return scene(std::to_string(k) + "-D wave grid, Dirichlet, n = " + size + ", u^3", s, q0,
               Eigen::VectorXd::Zero(d));
}

std::vector<Scene> scenes() {
  return {from_library(problems::fpu(3, 50), "FPU (m = 3, omega = 50)"),
          from_library(problems::sine_gordon(16), "sine-Gordon P1 (N = 16)"), wave_grid(15, 1),
          wave_grid(4, 2)};
}

enum class Outcome { refused, blew_up, bounded };

struct Run {
  Outcome outcome = Outcome::bounded;
  double error = 0;  // max relative energy error sampled (up to the stop); inf after an Error
  long steps = 0;    // steps taken
  std::string why;   // the erkn::Error that stopped it, if one did
  std::array<double, kCurve> curve{};  // the largest error over the first 2^k steps
};

// One run of `steps` steps of h against the criterion, stopping as soon as it is met.
Run run(const Method& m, const Scene& s, double h, long steps) {
  Options unguarded;
  unguarded.blowup_guard = false;
  Run r;
  std::unique_ptr<Integrator> it;
  try {
    it = std::make_unique<Integrator>(m, s.system, h, s.q0, s.p0, unguarded);
  } catch (const Error& e) {
    return {Outcome::refused, NAN, 0, e.what()};
  }
  const double H0 = it->energy();
  try {
    for (r.steps = 1; r.steps <= steps; ++r.steps) {
      it->step();
      if (r.steps % kSampleEvery == 0 || r.steps <= (1L << kDense))
        r.error = std::max(r.error, std::abs(it->energy() - H0) / std::abs(H0));
      if (std::has_single_bit(size_t(r.steps)) && std::bit_width(size_t(r.steps)) <= kCurve)
        r.curve[std::bit_width(size_t(r.steps)) - 1] = r.error;
      if (!(r.error < kBlowUp)) break;  // (NaN too)
    }
  } catch (const Error& e) {
    r.error = INFINITY, r.why = e.what();
  }
  for (int k = 1; k < kCurve; ++k)  // (after a stop, the curve stays at the stop's error)
    if (r.steps < (1L << k)) r.curve[k] = std::max(r.curve[k - 1], r.error);
  r.steps = std::min(r.steps, steps);
  if (!(r.error < kBlowUp)) r.outcome = Outcome::blew_up, r.error = std::max(r.error, kBlowUp);
  return r;
}

struct Point {
  size_t scene = 0, method = 0;
  double h_omega = 0;
  bool flagged = false, linear_flagged = false;  // the verdict; the linear model's alone
  std::string finding;                           // the advisor's first finding, when flagged
  TrialRun trial;                                // the verdict's trial run
  std::string linear;                            // the linear model's first hazard ("": none)
  Run at;                                        // the run at h
  double seconds = 0;
};

std::string first_finding(const StepSizeAdvice& advice, const Method& m) {
  const std::string report = advice.report(m);
  const size_t line = report.find('\n') + 1;
  return report.substr(line, report.find('\n', line) - line);
}

// The advisor's verdict and the runs at one point.
void measure(Point& pt, const Scene& s, const Method& m, long steps, long trial) {
  const auto start = std::chrono::steady_clock::now();
  const double h = pt.h_omega / s.omega;
  AdvisorOptions verdict_only;
  verdict_only.max_change = 0;  // (no search for a suggestion: only the verdict at h counts)
  verdict_only.steps = steps, verdict_only.trial_steps = trial;
  const StepSizeAdvice advice = advise_step_size(m, s.system, h, s.q0, s.p0, verdict_only);
  pt.flagged = !advice.safe(), pt.trial = advice.trial;
  verdict_only.trial_steps = 0;
  const StepSizeAdvice linear = advise_step_size(m, s.system, h, s.q0, s.p0, verdict_only);
  pt.linear_flagged = !linear.safe();
  if (pt.linear_flagged) pt.linear = to_string(linear.findings.front().hazard);
  if (pt.flagged) pt.finding = first_finding(advice, m);
  pt.at = run(m, s, h, steps);
  pt.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Args {
  long steps = 100000;
  int points = 16, threads = 2;
  double offset = 0;  // h omega = 4 pi (k - offset) / points
  long trial = AdvisorOptions{}.trial_steps;
  std::string out, csv;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 < argc && arg == "--steps")
      a.steps = std::stol(argv[++i]);
    else if (i + 1 < argc && arg == "--points")
      a.points = std::stoi(argv[++i]);
    else if (i + 1 < argc && arg == "--trial")
      a.trial = std::stol(argv[++i]);
    else if (i + 1 < argc && arg == "--offset")
      a.offset = std::stod(argv[++i]);
    else if (i + 1 < argc && arg == "--threads")
      a.threads = std::stoi(argv[++i]);
    else if (i + 1 < argc && arg == "--csv")
      a.csv = argv[++i];
    else if (arg.starts_with("-"))
      throw Error("erkn_advisor_sweep: unknown option " + arg);
    else
      a.out = arg;
  }
  if (a.steps < 1 || a.points < 1 || a.threads < 1 || a.trial < 1)
    throw Error("erkn_advisor_sweep: --steps, --points, --threads and --trial must be >= 1");
  if (!(a.offset >= 0 && a.offset < 1))
    throw Error("erkn_advisor_sweep: --offset must lie in [0, 1)");
  return a;
}

// Every point, measured on `threads` threads (each point is independent); the most expensive
// scenes (grids, implicit methods) first, so that no thread is left with a long tail.
std::vector<Point> sweep(const std::vector<Scene>& sc, const std::vector<Method>& ms,
                         const Args& a) {
  std::vector<Point> points;
  for (size_t s = sc.size(); s-- > 0;)
    for (size_t m = 0; m < ms.size(); ++m)
      for (int k = a.points; k >= 1; --k) {
        Point p;
        p.scene = s, p.method = m, p.h_omega = 4 * pi * (k - a.offset) / a.points;
        points.push_back(p);
      }
  std::atomic<size_t> next = 0, done = 0;
  auto work = [&] {
    for (size_t i; (i = next++) < points.size();) {
      measure(points[i], sc[points[i].scene], ms[points[i].method], a.steps, a.trial);
      if (++done % 100 == 0) std::cerr << done << "/" << points.size() << " points\n";
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < a.threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  return points;
}

struct Counts {
  long bounded_passed = 0, bounded_flagged = 0, blown_flagged = 0, blown_passed = 0, refused = 0;
  void add(const Point& p, bool flagged) {
    if (p.at.outcome == Outcome::refused) return void(++refused);
    if (p.at.outcome == Outcome::bounded)
      ++(flagged ? bounded_flagged : bounded_passed);
    else
      ++(flagged ? blown_flagged : blown_passed);
  }
};

std::string percent(long n, long of) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%ld / %ld = %.1f %%", n, of, of ? 100.0 * n / of : 0.0);
  return buf;
}

std::string row(const std::string& name, const Counts& c) {
  std::ostringstream s;
  s << "| " << name << " | " << c.bounded_passed << " | " << c.bounded_flagged << " | "
    << c.blown_flagged << " | " << c.blown_passed << " | " << c.refused << " | "
    << percent(c.bounded_flagged, c.bounded_flagged + c.bounded_passed) << " | "
    << percent(c.blown_passed, c.blown_flagged + c.blown_passed) << " |\n";
  return s.str();
}

std::string point_line(const Point& p, const std::vector<Scene>& sc,
                       const std::vector<Method>& ms) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "| %s | %s | %.4g | %s | %.3g | %ld | ", sc[p.scene].name.c_str(),
                std::string(ms[p.method].name()).c_str(), p.h_omega / pi,
                p.flagged ? "flagged" : "not flagged", p.at.error, p.at.steps);
  const std::string verdict = p.flagged ? p.finding.substr(p.finding.find_first_not_of(' '))
                                        : std::string("the method is stable at h");
  return buf + verdict + (p.at.why.empty() ? "" : "; run stopped: " + p.at.why) + " |\n";
}

// The rates over the methods that integrate M exactly (ERKN and the explicit splittings), per
// scene and over all; the RKN limits (M in the force, so H's error at h omega >~ 1 is their
// accuracy, not a growth the advisor could see) in rows of their own.
std::string rates_table(const std::vector<Point>& points, const std::vector<Scene>& sc,
                        const std::vector<Method>& ms, bool linear) {
  std::ostringstream s;
  s << "| scene | methods | bounded, not flagged | bounded, flagged (false alarm) | blew up, "
       "flagged | blew up, not flagged (miss) | refused at construction | false-alarm rate | "
       "miss rate |\n|---|---|---|---|---|---|---|---|---|\n";
  for (bool rkn : {false, true}) {
    const std::string kinds = rkn ? "RKN limits" : "ERKN and splittings";
    Counts all;
    for (size_t i = 0; i <= sc.size(); ++i) {
      Counts c;
      for (const Point& p : points)
        if ((ms[p.method].kind() == Kind::rkn) == rkn && (i == sc.size() || p.scene == i))
          c.add(p, linear ? p.linear_flagged : p.flagged);
      s << row((i == sc.size() ? "**all**" : sc[i].name) + " | " + kinds, c);
    }
  }
  return s.str();
}

// Which sweep the trial's constants were chosen on, and whether this one is another.
std::string sample_note(const Args& a) {
  std::ostringstream s;
  const AdvisorOptions o;
  s << "The trial run's constants (AdvisorOptions: trial_steps = " << o.trial_steps
    << ", extended_trial_steps = " << o.extended_trial_steps << ", ambiguity = " << o.ambiguity
    << ", saturated_margin = " << o.saturated_margin
    << ", explained_margin = " << o.explained_margin << ", trial_margin = " << o.trial_margin
    << "; the saturated growth and the quiet mode's least growth, advisor_trial.cpp) were "
       "chosen on a "
       "training sweep, `erkn_advisor_sweep --offset "
    << kTrainingOffset << "` (h omega = 4 pi (k - " << kTrainingOffset
    << ") / 16), from its per-point error curves (--csv). This run's step sizes are h omega = 4 "
       "pi (k - "
    << a.offset << ") / " << a.points << ": ";
  const bool training = a.offset == kTrainingOffset && a.points == 16;
  s << (training ? "the training set itself, so the rates below are in-sample."
                 : "none of them is in the training set, so the rates below are out of sample.");
  return s.str();
}

// The trial's mean length over the sweep, in steps and against the runs' length.
std::string mean_trial(const std::vector<Point>& points) {
  double sum = 0;
  long extended = 0;
  for (const Point& p : points)
    sum += double(p.trial.steps), extended += p.trial.steps > p.trial.first_steps;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%ld of %zu points extended, %.0f steps on average", extended,
                points.size(), sum / double(points.size()));
  return buf;
}

std::string report(const std::vector<Point>& points, const std::vector<Scene>& sc,
                   const std::vector<Method>& ms, const Args& a, double seconds, double cpu) {
  std::ostringstream s;
  s << "# The step-size advisor against runs\n\nWritten by `erkn_advisor_sweep` (experiments/src/"
       "advisor_sweep.cpp, whose header defines verdict, criterion and rates; scripts/main.sh "
       "runs it): "
    << ms.size() << " methods of the registry x " << sc.size() << " scenes x " << a.points
    << " step sizes h omega = 4 pi (k - " << a.offset << ") / " << a.points << ", runs of "
    << a.steps << " steps; a run blows up when its relative energy error reaches " << kBlowUp
    << " or a step fails. The sweep took " << std::lround(seconds) << " s on " << a.threads
    << " threads (" << std::lround(cpu) << " s of CPU time). " << sample_note(a)
    << "\n\nThe verdict (with the trial run of " << a.trial << " steps, extended to "
    << AdvisorOptions{}.extended_trial_steps << " where ambiguous: " << mean_trial(points)
    << "):\n\n"
    << rates_table(points, sc, ms, false)
    << "\nThe linear model alone (AdvisorOptions::trial_steps = 0), for comparison:\n\n"
    << rates_table(points, sc, ms, true)
    << "\nEvery disagreement (error: the run's largest sampled relative energy error, at least "
       "0.5 for a blow-up; steps: those run before it stopped):\n\n| scene | method | h omega / pi "
       "| advisor | "
       "error | steps | the advisor's finding; the run's stop |\n"
       "|---|---|---|---|---|---|---|\n";
  for (const Point& p : points)
    if (p.at.outcome != Outcome::refused && p.flagged == (p.at.outcome == Outcome::bounded))
      s << point_line(p, sc, ms);
  return s.str();
}

void write_csv(const std::string& file, const std::vector<Point>& points,
               const std::vector<Scene>& sc, const std::vector<Method>& ms) {
  std::ofstream out(file);
  out << "scene,method,kind,h_omega_over_pi,flagged,linear_flagged,linear,outcome,error,steps,"
         "seconds,trial_steps,trial_first_steps,trial_first_predicted,trial_error,trial_early,"
         "trial_predicted,trial_saturated,trial_failed,mode_rate,mode_share,takeover";
  for (int k = 0; k < kCurve; ++k) out << ",max_" << (1L << k);
  out << '\n';
  const char* outcome[] = {"refused", "blew_up", "bounded"};
  for (const Point& p : points) {
    out << '"' << sc[p.scene].name << "\",\"" << ms[p.method].name() << "\","
        << (ms[p.method].kind() == Kind::rkn ? "rkn" : "erkn") << ',' << p.h_omega / pi << ','
        << p.flagged << ',' << p.linear_flagged << ',' << p.linear << ','
        << outcome[int(p.at.outcome)] << ',' << p.at.error << ',' << p.at.steps << ',' << p.seconds
        << ',' << p.trial.steps << ',' << p.trial.first_steps << ',' << p.trial.first_predicted
        << ',' << p.trial.error << ',' << p.trial.early << ',' << p.trial.predicted << ','
        << p.trial.saturated << ',' << !p.trial.failure.empty() << ',' << p.trial.mode_rate << ','
        << p.trial.mode_share << ',' << p.trial.takeover;
    for (double e : p.at.curve) out << ',' << e;
    out << '\n';
  }
}

}  // namespace

int main(int argc, char** argv) try {
  const Args a = parse(argc, argv);
  const std::vector<Scene> sc = scenes();
  const std::vector<Method> ms(Method::all().begin(), Method::all().end());
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Point> points = sweep(sc, ms, a);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!a.csv.empty()) write_csv(a.csv, points, sc, ms);
  const std::string md = report(points, sc, ms, a, seconds, double(std::clock()) / CLOCKS_PER_SEC);
  if (a.out.empty()) {
    std::cout << md;
  } else {
    std::ofstream(a.out) << md;
    std::cout << "wrote " << a.out << "\n";
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "erkn_advisor_sweep: " << e.what() << "\n";
  return 1;
}
