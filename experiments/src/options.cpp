#include "options.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "problem.hpp"

namespace ex {
namespace {

// "A,B,C" -> {A, B, C}; an empty list or an empty item is refused (it would silently mean
// "all" or nothing).
std::vector<std::string> split(const std::string& option, const std::string& s) {
  std::vector<std::string> out;
  for (size_t start = 0;;) {
    const size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma - start));
    if (out.back().empty())
      throw std::invalid_argument(option +
                                  " expects a comma-separated list without empty items, "
                                  "got '" +
                                  s + "'");
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

// A whole string as a finite number, else an error naming the option and the value.
double number(const std::string& option, const std::string& value, const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(x))
    throw std::invalid_argument(option + " expects step sizes like 0.025 or 1/40, got '" + value +
                                "'");
  return x;
}

// "1/40" or "0.025" -> step count on [0, 10]; h must be finite, > 0 and at most 10.
long steps_of(const std::string& h_text) {
  const auto slash = h_text.find('/');
  const double h = slash == std::string::npos
                       ? number("--steps", h_text, h_text)
                       : number("--steps", h_text, h_text.substr(0, slash)) /
                             number("--steps", h_text, h_text.substr(slash + 1));
  if (!std::isfinite(h) || !(h > 0) || h > 10)
    throw std::invalid_argument("--steps: step size " + h_text +
                                " must be a finite number in (0, 10]");
  const double n = std::round(10 / h);
  if (n > 1e9) throw std::invalid_argument("--steps: step size " + h_text + " is too small");
  return std::max(1L, long(n));
}

void set_quick(RunConfig& c) {
  c.sweep.factor = 2;
  c.sweep.max_steps = 100000;
  c.sweep.timing = {5, 0.3, 0.02, 5, 5e-3};
}

void set_full(RunConfig& c) {
  c.sweep.factor = std::sqrt(2.0);
  c.sweep.max_steps = 2000000;
  c.sweep.timing = {7, 1.0, 0.05, 9, 0.01};
}

}  // namespace

std::string usage() {
  return "usage: erkn-experiments [--quick | --full] [--problems "
         "P1,P2,P3,FPU,HH,scaling,stiff,grids]\n"
         "                        [--methods NAME,...] [--methods-file F.json] [--steps H,...]\n"
         "                        [--out DIR] [--list]\n"
         "  --quick      small sweep (default): step factor 2, best of up to 5 timings, the\n"
         "               deciding runs timed again in 5 interleaved rounds\n"
         "  --full       fine sweep: step factor sqrt 2, up to 2e6 steps, best of 7 timings,\n"
         "               9 interleaved rounds\n"
         "  --problems   which scenes to run (default: all; grids writes DIR/grids.md)\n"
         "  --methods    the paper's names, e.g. SERKN3s4(1),RKN3s4(1),Gauss2 (default: all)\n"
         "  --methods-file F.json  adds the explicit methods of F (erkn-generate --json), checked\n"
         "               against the order conditions they claim; repeatable\n"
         "  --steps      fixed step sizes on [0, 10], e.g. 1/40,1/80 (no extension)\n"
         "  --out DIR    writes DIR/results.md and DIR/charts/ (default: docs)\n"
         "  --list       lists the problems and methods and exits\n"
         "  --help       prints this and exits\n";
}

Options parse_options(int argc, char** argv) {
  Options o;
  set_quick(o.config);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--quick")
      o.mode = "quick", set_quick(o.config);
    else if (arg == "--full")
      o.mode = "full", set_full(o.config);
    else if (arg == "--problems")
      o.problems = split(arg, value());
    else if (arg == "--methods")
      o.methods = split(arg, value());
    else if (arg == "--methods-file")
      o.methods_files.push_back(value());
    else if (arg == "--steps") {
      o.config.steps.clear();
      for (const std::string& h : split(arg, value())) o.config.steps.push_back(steps_of(h));
    } else if (arg == "--out")
      o.out = value();
    else if (arg == "--list")
      o.list = true;
    else if (arg == "--help" || arg == "-h")
      o.help = true;
    else
      throw std::invalid_argument("unknown option " + arg);
  }
  if (!o.config.steps.empty()) o.mode = "custom";
  // The problem keys are the problems library's (problem_by_key refuses the others).
  for (const std::string& p : o.problems) {
    if (p == "scaling" || p == "stiff" || p == "grids") continue;
    try {
      problem_by_key(p);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) + "; scenes: scaling, stiff, grids");
    }
  }
  return o;
}

}  // namespace ex
