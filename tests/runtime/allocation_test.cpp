// A step allocates nothing, on every structure of M, for ERKN and RKN methods alike, nor a read of
// the state after steps but the blow-up guard's checkpoint; an explicit integrator of a small
// dimension is built from blocks that glibc's per-thread cache serves.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <erkn/compiled_gradient.hpp>
#include <optional>
#include <thread>

#include "problems.hpp"

// Every block asked of malloc, calloc or realloc counted, whoever asks: operator new and Eigen's
// dynamic arrays (which call std::malloc: counting operator new alone missed FlowCoefficients'
// 1152-1728 bytes with a diagonal M of d <= 4) alike. glibc's own entries under these names serve
// them.
namespace {
std::atomic<long> allocations{0};
std::atomic<std::size_t> largest{0};  // the largest block asked for since it was reset
std::atomic<long> large{0};  // blocks asked for of more than glibc's per-thread cache serves
constexpr std::size_t kLargeBytes = 1032;
void note(std::size_t n) {
  ++allocations;
  if (n > kLargeBytes) ++large;
  for (std::size_t seen = largest; n > seen && !largest.compare_exchange_weak(seen, n);) {
  }
}
}  // namespace
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* malloc(std::size_t n) {
  note(n);
  return __libc_malloc(n);
}
void* calloc(std::size_t k, std::size_t n) {
  note(k * n);
  return __libc_calloc(k, n);
}
void* realloc(void* p, std::size_t n) {
  note(n);
  return __libc_realloc(p, n);
}
}

namespace erkn::test {
namespace {

// M in each structure: scalar, and sine-Gordon's N-point circulant as a diagonal (its
// diagonal), circulant and dense matrix.
std::array<Stiffness, 4> every_structure(int N) {
  const Stiffness circ = Stiffness::circulant(sine_gordon_column(N));
  return {Stiffness::scalar(50), Stiffness::diagonal(circ.to_dense(N).diagonal()), circ,
          Stiffness::dense(circ.to_dense(N))};
}

TEST(Allocation, StepAllocatesNothing) {
  const int N = 16;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(N, q0, p0);
  const std::array<Stiffness, 4> forms = every_structure(N);
  for (const Method& m : Method::all())
    for (const Stiffness& M : forms) {
      SCOPED_TRACE(std::string(m.name()) + " structure " + std::to_string(int(M.structure())));
      Integrator run(m, sine_gordon(M), 1.0 / 40, q0, p0);
      run.step();  // warm-up: FFT plans and twiddles are built on first use
      const long before = allocations;
      for (int k = 0; k < 10; ++k) run.step();
      EXPECT_EQ(allocations - before, 0);
      EXPECT_EQ(run.statistics().newton_fallbacks, 0);
    }
}

// Steps and the first read of the state after them: without the blow-up guard they allocate
// nothing (no checkpoint is kept); with it (the negative control) the checkpoint's q and p, to
// which a failed check would return, once. Every method, every structure of M.
TEST(Allocation, StepsAndAReadAllocateOnlyTheGuardsCheckpoint) {
  const int N = 16;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(N, q0, p0);
  const std::array<Stiffness, 4> forms = every_structure(N);
  for (const Method& m : Method::all())
    for (const Stiffness& M : forms)
      for (const bool guard : {false, true}) {
        SCOPED_TRACE(std::string(m.name()) + " structure " + std::to_string(int(M.structure())) +
                     (guard ? " guard on" : " guard off"));
        Options o;
        o.blowup_guard = guard;
        Integrator warm(m, sine_gordon(M), 1.0 / 40, q0, p0, o);
        warm.step();  // (FFT plans and twiddles are built on first use)
        warm.q();
        Integrator run(m, sine_gordon(M), 1.0 / 40, q0, p0, o);
        const long before = allocations;
        for (int k = 0; k < 3; ++k) run.step();  // (a processed method's steps read the state)
        run.q(), run.p();
        EXPECT_EQ(allocations - before, guard ? 2 : 0);
        run.step();
        const long again = allocations;
        run.q(), run.p();  // (the checkpoint stays out of q, p until a check passes)
        EXPECT_EQ(allocations - again, 0);
      }
}

// glibc's malloc serves blocks of up to 1032 bytes from a per-thread cache (tcache) of freed
// ones; a larger block takes the bins, and first merges the freed small chunks (fastbins) when
// there are any, as in a process that builds and drops integrators. The explicit stepper (one
// block) had grown to 1408 bytes at d = 1 (FlowCoefficients' 64 doubles inside it): the
// Integrator's constructor then cost 3548 instructions in erkn_explicit_benchmark's setup cells
// against 2758 before (callgrind; 233 in malloc_consolidate), 1.15-1.6x the time. With a
// diagonal M, FlowCoefficients' own block (a cache line per array, aligned_stride) was 1152-1728
// bytes for 6 methods at d = 1..4, which this test, counting operator new alone, did not see: in
// a user's loop of construct + 20 steps of P3 with small frees in between, 1.8-2.5 % of the time
// in malloc_consolidate (perf).
TEST(Allocation, SmallExplicitIntegratorsUseCachedBlocks) {
  constexpr std::size_t kCached = 1032;
  for (int d = 1; d <= 4; ++d) {  // (the fixed dimensions: the stepper holds its arrays)
    const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, 0.1, 0.4), p0 = q0.reverse();
    const Stiffness forms[] = {Stiffness::scalar(50),
                               Stiffness::diagonal(Eigen::VectorXd::LinSpaced(d, 20, 50))};
    for (const Method& m : Method::all())
      for (const Stiffness& M : forms) {
        if (!m.is_explicit()) continue;  // (the stage solver's stepper is larger: not asked)
        SCOPED_TRACE(std::string(m.name()) + " d = " + std::to_string(d) + " structure " +
                     std::to_string(int(M.structure())));
        largest = 0;
        Integrator run(m, sine_gordon(M), 1.0 / 40, q0, p0);
        EXPECT_LE(largest.load(), kCached);
        EXPECT_GT(largest.load(), 0u);  // (the stepper's block was seen)
        // The same with the gradient compiled in (erkn/compiled_gradient.hpp), a functor of 8
        // bytes.
        largest = 0;
        System bare = sine_gordon(M);
        bare.gradient = nullptr;
        const double kappa = 1;
        const auto sine = [kappa](const auto& q, auto& g) { g = kappa * q.array().sin().matrix(); };
        Integrator compiled = make_integrator(m, bare, sine, 1.0 / 40, q0, p0);
        EXPECT_LE(largest.load(), kCached);
        EXPECT_GT(largest.load(), 0u);
      }
  }
  largest = 0;  // (negative controls: a larger block is seen as one, through Eigen's too)
  ::operator delete(::operator new(kCached + 1));
  EXPECT_EQ(largest.load(), kCached + 1);
  largest = 0;
  Eigen::ArrayXd eigens(kCached / sizeof(double) + 1);
  static double* volatile kept;  // (so the compiler keeps the block)
  kept = eigens.data();
  EXPECT_EQ(largest.load(), kCached + sizeof(double));
}

// The implicit stepper (~10.8 KB at d = 2: above glibc's per-thread cache) takes the block its
// thread's last one of the same size gave back (block_pool.hpp: take_kept_block): construct +
// integrate again asks malloc for one block above the cache's limit fewer than on a new thread,
// for every implicit method and fixed dimension. Negative control: with the first still alive, a
// second one asks for as many as on a new thread.
TEST(Allocation, ImplicitIntegratorsReuseTheirThreadsBlock) {
  const auto large_blocks = [&](const auto& run) {
    const long before = large;
    run();
    return large - before;
  };
  for (int d = 1; d <= 4; ++d) {
    const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, 0.1, 0.4), p0 = q0.reverse();
    const System sys = sine_gordon(Stiffness::diagonal(Eigen::VectorXd::LinSpaced(d, 20, 50)));
    const double h = 1.0 / 32, t_end = 4 * h;  // (on the grid: no stepper for a shorter step)
    for (const Method& m : Method::all()) {
      if (m.is_explicit()) continue;
      SCOPED_TRACE(std::string(m.name()) + " d = " + std::to_string(d));
      const auto construct_and_integrate = [&] { Integrator(m, sys, h, q0, p0).integrate(t_end); };
      construct_and_integrate();  // (the method's predictor nodes formed once: stage_nodes.hpp)
      long on_new_thread = 0;
      std::thread([&] { on_new_thread = large_blocks(construct_and_integrate); }).join();
      EXPECT_GE(on_new_thread, 1);
      construct_and_integrate();  // (its block kept)
      std::optional<Integrator> first;
      EXPECT_EQ(large_blocks([&] { first.emplace(m, sys, h, q0, p0).integrate(t_end); }),
                on_new_thread - 1);
      EXPECT_EQ(large_blocks(construct_and_integrate), on_new_thread);
    }
  }
}

// The stage solver's vectors that the callbacks see (Q and g) are kept per thread like the
// stepper's block (block_pool.hpp: take_kept_vectors): construct + integrate after another has
// gone asks malloc for three blocks fewer (the block, Q and g) than one while another is alive
// (which holds them), for every implicit method, on every structure of M (a fixed dimension,
// dynamic ones, a transform).
TEST(Allocation, ImplicitIntegratorsReuseTheirThreadsVectors) {
  const auto allocations_of = [&](const auto& run) {
    const long before = allocations;
    run();
    return allocations - before;
  };
  const int d = 8;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(d, q0, p0);
  const std::array<Stiffness, 4> forms = every_structure(d);
  const double h = 1.0 / 40, t_end = 4 * h;
  for (const Method& m : Method::all()) {
    if (m.is_explicit()) continue;
    for (const Stiffness& M : forms) {
      SCOPED_TRACE(std::string(m.name()) + " structure " + std::to_string(int(M.structure())));
      const System sys = sine_gordon(M);
      const auto construct_and_integrate = [&] { Integrator(m, sys, h, q0, p0).integrate(t_end); };
      construct_and_integrate();  // (plans, nodes: formed once per process)
      std::optional<Integrator> first;
      first.emplace(m, sys, h, q0, p0).integrate(t_end);  // (takes what the thread kept)
      const long beside_first = allocations_of(construct_and_integrate);
      first.reset();
      EXPECT_EQ(allocations_of(construct_and_integrate), beside_first - 3);
    }
  }
}

}  // namespace
}  // namespace erkn::test
