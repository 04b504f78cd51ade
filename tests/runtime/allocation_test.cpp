// A step allocates nothing, on every structure of M, for ERKN and RKN methods alike.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "problems.hpp"

namespace {
std::atomic<long> allocations{0};
}

void* operator new(std::size_t n) {
  ++allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace erkn::test {
namespace {

TEST(Allocation, StepAllocatesNothing) {
  const int N = 16;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(N, q0, p0);
  const Stiffness circ = Stiffness::circulant(sine_gordon_column(N));
  const Stiffness forms[] = {Stiffness::scalar(50),
                             Stiffness::diagonal(circ.to_dense(N).diagonal()), circ,
                             Stiffness::dense(circ.to_dense(N))};
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

}  // namespace
}  // namespace erkn::test
