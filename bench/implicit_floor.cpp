// erkn_implicit_floor (issue 17): CPU per grad U of the loop a specialist writes for each implicit
// registry method (bench/implicit_floor.hpp), on Duffing (P2, d = 1, h = 0.01, 1000 steps) and
// the stellar orbits (P3, d = 2, h = 1/40, 400 steps), against the explicit path's (erkn's
// explicit registry methods through System::gradient, defaults, construct + integrate: their
// median per grad U per round, as erkn_integrate_benchmark's add_implicit) and against the
// explicit specialist peers' (bench/specialist_peer.hpp, gradient inlined), in one process,
// interleaved rounds (bench/integrate_timing.hpp), thread pinned. Also erkn's implicit method in
// the same rounds; cb+ is the callback loop with erkn's compensated summation and finiteness
// checks, carry the loop with the next step's first Q_0 formed at the end of a step. Before timing,
// every loop's final state is compared with erkn's (the report's column).
//
//   erkn_implicit_floor [--short] [--order K]
#include "implicit_floor.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "implicit_floor_runs.hpp"
#include "integrate_timing.hpp"

namespace {

using namespace bench;

// The report of one scene: per implicit method the ratios' medians over rounds.
void report(const floor::SceneResult& r) {
  std::printf(
      "\n## %s: explicit path %.2f ns per grad U (erkn, median of %d methods), peers %.2f\n",
      r.label.c_str(), 1e9 * r.explicit_s, r.explicit_methods, 1e9 * r.peer_s);
  std::printf(
      "| method | grad U/step erkn | floor | max abs state diff | floor inl / expl | floor cb / "
      "expl | floor cb+ / expl | floor inl carry / expl | floor cb carry / expl | erkn / expl | "
      "floor inl / peers | floor cb / peers | erkn / floor cb | erkn / floor cb+ | "
      "floor cb us/step |\n|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const floor::MethodResult& m : r.methods)
    std::printf(
        "| %s | %.3f | %.3f | %.1e | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | "
        "%.3f | %.3f | %.4f |\n",
        m.name.c_str(), m.erkn_per_step, m.floor_per_step, m.state_diff, m.inl_expl, m.cb_expl,
        m.extras_expl, m.inl_carry_expl, m.cb_carry_expl, m.erkn_expl, m.inl_peer, m.cb_peer,
        m.erkn_cb, m.erkn_extras, 1e6 * m.cb_step_s);
}

}  // namespace

int main(int argc, char** argv) {
  bool short_mode = false;
  floor::Settings settings;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--short") == 0) {
      short_mode = true;
    } else if (std::strcmp(argv[a], "--order") == 0 && a + 1 < argc) {
      settings.order = std::atoi(argv[++a]);
    } else {
      std::fprintf(stderr, "usage: erkn_implicit_floor [--short] [--order K]\n");
      return 2;
    }
  }
  const bool pinned = pin_to_one_cpu();
  Schedule schedule;
  std::vector<floor::SceneResult> results(2);
  floor::add_scene<1>(floor::duffing_scene(short_mode), DuffingGradient{}, settings, schedule,
                      results[0]);
  floor::add_scene<2>(floor::stellar_scene(short_mode), StellarGradient{}, settings, schedule,
                      results[1]);
  schedule.run(short_mode ? TimingPlan{5, 4e-3} : TimingPlan{9, 1e-2});
  std::printf("# implicit floor (thread %s)\n", pinned ? "pinned" : "not pinned");
  for (const auto& r : results) report(r);
  return 0;
}
