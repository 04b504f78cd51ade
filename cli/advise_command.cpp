// erkn advise NAME --h H (--spectrum L1,L2,... | --problem P1|P2|P3|FPU) [--hessian LO,HI]
//
// --spectrum: eigenvalues of M; the Hessian bounds default to [0, 0] (U = 0) unless --hessian.
// --problem:  a problem of erkn::problems, with M's eigenvalues, the Hessian bounds at its
//             initial state and its initial mode energies (a resonance needs an excited mode;
//             with --spectrum every mode counts as excited), judged by a trial run of the
//             problem (erkn/advisor.hpp, "Severity") for a run of --steps N steps (default 1e5);
//             with --hessian, the linear model alone.
#include "advise_command.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <erkn/problems.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "erkn/advisor.hpp"
#include "erkn/error.hpp"
#include "help.hpp"

namespace erkn::cli {
namespace {

double number(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || std::isspace((unsigned char)text[0]) || end != text.c_str() + text.size() ||
      !std::isfinite(x))
    throw Error(option + " expects finite numbers, got '" + text + "'");
  return x;
}

// "a,b,c" -> numbers; an empty list or item is refused.
std::vector<double> numbers(const std::string& option, const std::string& text) {
  std::vector<double> out;
  for (size_t start = 0;;) {
    const size_t comma = text.find(',', start);
    out.push_back(number(option, text.substr(start, comma - start)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

// A whole number of steps >= 1.
long steps_number(const std::string& option, const std::string& text) {
  const double x = number(option, text);
  if (x < 1 || x > 1e15 || x != std::floor(x))
    throw Error(option + " expects a whole number of steps >= 1, got '" + text + "'");
  return long(x);
}

int usage(bool help = false) {
  return print_usage(
      "usage: erkn advise NAME --h H (--spectrum L1,L2,... | --problem P1|P2|P3|FPU)"
      " [--hessian LO,HI] [--steps N]\n"
      "  step sizes near H the stability analysis warns against, and the nearest one it does\n"
      "  not; with --problem (and no --hessian) a trial run of the problem judges whether a run\n"
      "  of N steps (default 100000) keeps its energy; exit 0: H is not flagged, 3: flagged\n"
      "  (the report says why)\n",
      help);
}

// --spectrum: the linear model over the given eigenvalues, every mode excited.
StepSizeAdvice advise_spectrum(const Method& method, double h, const std::vector<double>& spectrum,
                               const std::vector<double>& hessian, const AdvisorOptions& options) {
  const Eigen::VectorXd lambda =
      Eigen::Map<const Eigen::VectorXd>(spectrum.data(), Eigen::Index(spectrum.size()));
  const HessianBounds bounds =
      hessian.empty() ? HessianBounds{} : HessianBounds{hessian[0], hessian[1]};
  return advise_step_size(method, lambda, h, bounds, options);
}

// --problem: the problem's own state and a trial run; with --hessian, the linear model with
// those bounds and the initial mode energies.
StepSizeAdvice advise_problem(const Method& method, double h, const std::string& key,
                              const std::vector<double>& hessian, const AdvisorOptions& options) {
  const problems::Problem p = problems::problem_by_key(key);
  const System system = problems::system(p);
  if (hessian.empty()) return advise_step_size(method, system, h, p.q0, p.p0, options);
  return advise_step_size(method, system.M.eigenvalues(), h, {hessian[0], hessian[1]}, options,
                          mode_energies(system.M, p.q0, p.p0));
}

}  // namespace

int advise_command(int argc, char** argv) {
  if (asks_for_help(argc, argv)) return usage(true);
  std::string name, problem;
  std::vector<double> spectrum, hessian;
  double h = std::nan("");
  AdvisorOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw Error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--h")
      h = number(arg, value());
    else if (arg == "--spectrum")
      spectrum = numbers(arg, value());
    else if (arg == "--problem")
      problem = value();
    else if (arg == "--steps")
      options.steps = steps_number(arg, value());
    else if (arg == "--hessian") {
      hessian = numbers(arg, value());
      if (hessian.size() != 2) throw Error("--hessian expects two numbers LO,HI");
    } else if (arg.rfind("--", 0) == 0)
      throw Error("unknown option " + arg);
    else if (name.empty())
      name = arg;
    else
      return usage();
  }
  if (name.empty() || std::isnan(h) || spectrum.empty() == problem.empty()) return usage();
  const Method& method = Method::by_name(name);
  const StepSizeAdvice advice = problem.empty()
                                    ? advise_spectrum(method, h, spectrum, hessian, options)
                                    : advise_problem(method, h, problem, hessian, options);
  std::cout << advice.report(method);
  return advice.safe() ? 0 : 3;
}

}  // namespace erkn::cli
