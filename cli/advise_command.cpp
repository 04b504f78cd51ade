// erkn advise NAME --h H (--spectrum L1,L2,... | --problem P1|P2|P3|FPU) [--hessian LO,HI]
//
// --spectrum: eigenvalues of M; the Hessian bounds default to [0, 0] (U = 0) unless --hessian.
// --problem:  a problem of erkn::problems, with M's eigenvalues, the Hessian bounds at its
//             initial state (or --hessian) and its initial mode energies (a resonance needs an
//             excited mode; with --spectrum every mode counts as excited).
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

int usage(bool help = false) {
  return print_usage(
      "usage: erkn advise NAME --h H (--spectrum L1,L2,... | --problem P1|P2|P3|FPU)"
      " [--hessian LO,HI]\n"
      "  step sizes near H the stability analysis warns against, and the nearest one it does\n"
      "  not; exit 0: H is not flagged, 3: flagged (the report says why)\n",
      help);
}

}  // namespace

int advise_command(int argc, char** argv) {
  if (asks_for_help(argc, argv)) return usage(true);
  std::string name, problem;
  std::vector<double> spectrum, hessian;
  double h = std::nan("");
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
  HessianBounds bounds;
  Eigen::VectorXd lambda, energy;
  if (!problem.empty()) {
    const problems::Problem p = problems::problem_by_key(problem);
    const System system = problems::system(p);
    lambda = system.M.eigenvalues();
    energy = mode_energies(system.M, p.q0, p.p0);
    bounds = hessian.empty() ? hessian_bounds_at(system, p.q0) : HessianBounds{};
  } else {
    lambda = Eigen::Map<const Eigen::VectorXd>(spectrum.data(), Eigen::Index(spectrum.size()));
  }
  if (!hessian.empty()) bounds = {hessian[0], hessian[1]};
  const StepSizeAdvice advice = advise_step_size(method, lambda, h, bounds, {}, energy);
  std::cout << advice.report(method);
  return advice.safe() ? 0 : 3;
}

}  // namespace erkn::cli
