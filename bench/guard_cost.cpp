// erkn_guard_cost: the cost of Options::blowup_guard (on by default). CPU time (this thread) per
// step with the guard on and off, alternated in one process over 7 rounds, best of each, on the
// paper's problems P1-P3 for two explicit methods and an implicit one; prints on / off. The
// target (issue 21): at most 1.02.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>

namespace {

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Seconds per step of `steps` steps with the guard on or off.
double per_step(const char* method, const erkn::problems::Problem& pr, double h, long steps,
                bool guard) {
  erkn::Options o;
  o.blowup_guard = guard;
  erkn::Integrator run(erkn::Method::by_name(method), erkn::problems::system(pr), h, pr.q0, pr.p0,
                       o);
  const double start = cpu_seconds();
  for (long n = 0; n < steps; ++n) run.step();
  return (cpu_seconds() - start) / double(steps);
}

}  // namespace

int main() {
  struct Case {
    const char* key;
    double h;
    long steps;
  };
  for (const Case c : {Case{"P1", 0.01, 20000}, Case{"P2", 0.01, 100000}, Case{"P3", 0.05, 100000}})
    for (const char* method : {"Strang", "SABA2", "SERKN2s4"}) {
      const auto pr = erkn::problems::problem_by_key(c.key);
      double best[2] = {1e9, 1e9};
      for (int round = 0; round < 7; ++round)
        for (int guard : {round % 2, 1 - round % 2})  // (alternating which goes first)
          best[guard] = std::min(best[guard], per_step(method, pr, c.h, c.steps, guard));
      std::printf("%s %-9s off %7.1f ns  on %7.1f ns per step  on/off %.4f\n", c.key, method,
                  1e9 * best[0], 1e9 * best[1], best[1] / best[0]);
    }
}
