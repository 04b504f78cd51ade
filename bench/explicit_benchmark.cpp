// erkn's explicit path against a hand-written splitting integrator of the same method (same
// nodes, weights and gradient code; bench/splitting_peer.hpp), in the same run: time per grad U
// evaluation and setup time (thread CPU time), each as a ratio erkn / peer, and the share of a step
// spent outside grad U (the gradient timed alone on the same states). Problems: P1 sine-Gordon (N =
// 32, circulant M), P2 Duffing (d = 1), P3 stellar orbits (d = 2), DESIGN.md section 4.
//
// Methods: every registry method whose diagonal abar_ii is identically 0; until the registry has
// one, Strang (c = 1/2) and the kick-flow-kick form (c = 0, 1) built here from their nodes.
//
//   erkn_explicit_benchmark [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>
#include <erkn/erkn.hpp>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "splitting_peer.hpp"

namespace {

// CPU time of this thread: the machine is shared, so wall time would count other programs.
double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

std::vector<erkn::Method> explicit_methods() {
  std::vector<erkn::Method> out;
  for (const erkn::Method& m : erkn::Method::all()) {
    const int s = m.stages();
    bool zero = true;
    for (int i = 0; i < s; ++i)
      zero &= std::string_view(m.table().closed_forms[2 * s + i * (i + 1) / 2 + i]) == "0";
    if (zero && m.kind() == erkn::Kind::erkn) out.push_back(m);
  }
  if (!out.empty()) return out;
  // Stand-ins (the explicit path reads only c, d and the diagonal's closed forms).
  static const double c1[] = {0.5, 0, 0}, d1[] = {1, 0, 0}, c2[] = {0, 1, 0}, d2[] = {0.5, 0.5, 0};
  static const char* zero[] = {"", "", "", "", "0", "", "0", "", ""};
  static erkn::generated::Table strang = erkn::Method::all()[0].table(), kfk = strang;
  strang.name = "Strang (c = 1/2)", strang.stages = 1, strang.c = c1, strang.d = d1;
  kfk.name = "kick-flow-kick (c = 0, 1)", kfk.stages = 2, kfk.c = c2, kfk.d = d2;
  static const char* zero1[] = {"", "", "0"};
  strang.closed_forms = zero1, kfk.closed_forms = zero;
  strang.npoles = kfk.npoles = 0;
  const erkn::MethodId id = erkn::Method::all()[0].id();
  return {erkn::Method(id, &strang), erkn::Method(id, &kfk)};
}

// The three problems: their gradient (one body for both integrators), M and initial state.
struct P1 {
  using Vec = Eigen::ArrayXd;
  static constexpr int N = 32;
  static constexpr double h = 1.0 / 40;
  static void grad(const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); }
  static void grad_peer(const Vec& q, Vec& g) { g = q.sin(); }
  static Eigen::VectorXd column() {
    const double dx = 2.0 / N;
    Eigen::VectorXd col = Eigen::VectorXd::Zero(N);
    col[0] = 2 / (dx * dx), col[1] = col[N - 1] = -1 / (dx * dx);
    return col;
  }
  static erkn::Stiffness M() { return erkn::Stiffness::circulant(column()); }
  static bench::FourierBasis basis() { return bench::FourierBasis(column().array()); }
  static Eigen::VectorXd q0() { return Eigen::VectorXd::Constant(N, std::numbers::pi); }
  static Eigen::VectorXd p0() {
    Eigen::VectorXd p(N);
    for (int i = 0; i < N; ++i)
      p[i] = std::sqrt(double(N)) * (0.01 + std::sin(2 * std::numbers::pi * (i + 1) / N));
    return p;
  }
};

struct P2 {
  using Vec = Eigen::Array<double, 1, 1>;
  static constexpr double h = 1.0 / 100, k2 = 0.03 * 0.03;
  static void grad(const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g[0] = k2 * (q[0] - 2 * q[0] * q[0] * q[0]);
  }
  static void grad_peer(const Vec& q, Vec& g) { g[0] = k2 * (q[0] - 2 * q[0] * q[0] * q[0]); }
  static erkn::Stiffness M() { return erkn::Stiffness::scalar(100); }
  static bench::DiagonalBasis<Vec> basis() { return {Vec::Constant(100)}; }
  static Eigen::VectorXd q0() { return Eigen::VectorXd::Zero(1); }
  static Eigen::VectorXd p0() { return Eigen::VectorXd::Constant(1, 10); }
};

struct P3 {
  using Vec = Eigen::Array2d;
  static constexpr double h = 1.0 / 8, eps = 1e-3;
  static void grad(const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g[0] = -eps * q[1] * q[1];
    g[1] = -2 * eps * q[0] * q[1];
  }
  static void grad_peer(const Vec& q, Vec& g) {
    g[0] = -eps * q[1] * q[1];
    g[1] = -2 * eps * q[0] * q[1];
  }
  static erkn::Stiffness M() { return erkn::Stiffness::diagonal(Eigen::Vector2d(4, 1)); }
  static bench::DiagonalBasis<Vec> basis() { return {Vec(4, 1)}; }
  static Eigen::VectorXd q0() { return Eigen::VectorXd::Ones(2); }
  static Eigen::VectorXd p0() { return Eigen::VectorXd::Zero(2); }
};

template <class P>
auto make_peer(const erkn::Method& m) {
  using Vec = typename P::Vec;
  const Vec q0 = P::q0().array(), p0 = P::p0().array();
  return bench::SplittingPeer(m.table().c, m.table().d, m.stages(), P::h, P::basis(), &P::grad_peer,
                              q0, p0);
}

template <class P>
erkn::System make_system() {
  erkn::System sys;
  sys.M = P::M();
  sys.gradient = &P::grad;
  return sys;
}

template <class P>
erkn::Integrator make_erkn(const erkn::Method& m, bool compensated) {
  erkn::Options o;
  o.compensated_summation = compensated;
  return erkn::Integrator(m, make_system<P>(), P::h, P::q0(), P::p0(), o);
}

template <class F>
double seconds(F&& f) {
  const double start = cpu_seconds();
  f();
  return cpu_seconds() - start;
}

// Per grad U evaluation: erkn (plain and compensated summation) and the peer, in alternating
// batches of steps; the gradient alone on the erkn trajectory's q gives the share outside it.
template <class P>
void per_evaluation(benchmark::State& state) {
  const erkn::Method m = explicit_methods().at(size_t(state.range(0)));
  state.SetLabel(std::string(m.name()));
  erkn::Integrator plain = make_erkn<P>(m, false), kahan = make_erkn<P>(m, true);
  auto peer = make_peer<P>(m);
  const int batch = 256;
  double t_plain = 0, t_kahan = 0, t_peer = 0, t_grad = 0;
  long e0 = plain.statistics().gradient_evaluations, p0 = peer.evaluations();
  Eigen::VectorXd g = P::q0();
  for (auto _ : state) {
    t_plain += seconds([&] {
      for (int k = 0; k < batch; ++k) plain.step();
    });
    t_kahan += seconds([&] {
      for (int k = 0; k < batch; ++k) kahan.step();
    });
    t_peer += seconds([&] {
      for (int k = 0; k < batch; ++k) peer.step();
    });
    const Eigen::VectorXd& q = plain.q();
    t_grad += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        P::grad(q, g);
        benchmark::DoNotOptimize(g.data());
      }
    });
  }
  const double evals = double(plain.statistics().gradient_evaluations - e0);
  const double peer_evals = double(peer.evaluations() - p0);
  const double per_grad = t_grad / (double(state.iterations()) * batch);
  state.counters["erkn_ns/eval"] = 1e9 * t_plain / evals;
  state.counters["erkn_kahan_ns/eval"] = 1e9 * t_kahan / evals;
  state.counters["peer_ns/eval"] = 1e9 * t_peer / peer_evals;
  state.counters["ratio"] = (t_plain / evals) / (t_peer / peer_evals);
  state.counters["ratio_kahan"] = (t_kahan / evals) / (t_peer / peer_evals);
  state.counters["erkn_outside_gradU"] = 1 - per_grad * evals / t_plain;
  state.counters["peer_outside_gradU"] = 1 - per_grad * peer_evals / t_peer;
  benchmark::DoNotOptimize(peer.q().data());
}

// Setup: constructing the integrator (default options) against constructing the peer, each
// from the problem's definition (erkn: System and Stiffness included); and the Integrator's
// constructor alone, from a System and initial state built beforehand.
template <class P>
void setup(benchmark::State& state) {
  const erkn::Method m = explicit_methods().at(size_t(state.range(0)));
  state.SetLabel(std::string(m.name()));
  const int batch = 16;
  const erkn::System system = make_system<P>();
  const Eigen::VectorXd q0 = P::q0(), p0 = P::p0();
  double t_erkn = 0, t_peer = 0, t_ctor = 0;
  for (auto _ : state) {
    t_ctor += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        erkn::Integrator run(m, system, P::h, q0, p0);
        benchmark::DoNotOptimize(&run);
      }
    });
    t_erkn += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        erkn::Integrator run = make_erkn<P>(m, true);
        benchmark::DoNotOptimize(&run);
      }
    });
    t_peer += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        auto peer = make_peer<P>(m);
        benchmark::DoNotOptimize(&peer);
      }
    });
  }
  const double n = double(state.iterations()) * batch;
  state.counters["erkn_us"] = 1e6 * t_erkn / n;
  state.counters["peer_us"] = 1e6 * t_peer / n;
  state.counters["ratio"] = t_erkn / t_peer;
  state.counters["erkn_ctor_us"] = 1e6 * t_ctor / n;
  state.counters["ratio_ctor"] = t_ctor / t_peer;
}

}  // namespace

// Registered in main: the methods come from the registry, which static initialisation of the
// benchmarks would read before it exists.
int main(int argc, char** argv) {
  const std::vector<erkn::Method> methods = explicit_methods();
  for (size_t i = 0; i < methods.size(); ++i) {
    const std::string name = std::string(methods[i].id_name()) + "/" + std::to_string(i);
    benchmark::RegisterBenchmark(("PerEvaluation/P1/" + name).c_str(), per_evaluation<P1>)
        ->Arg(long(i));
    benchmark::RegisterBenchmark(("PerEvaluation/P2/" + name).c_str(), per_evaluation<P2>)
        ->Arg(long(i));
    benchmark::RegisterBenchmark(("PerEvaluation/P3/" + name).c_str(), per_evaluation<P3>)
        ->Arg(long(i));
    benchmark::RegisterBenchmark(("Setup/P1/" + name).c_str(), setup<P1>)->Arg(long(i));
    benchmark::RegisterBenchmark(("Setup/P2/" + name).c_str(), setup<P2>)->Arg(long(i));
    benchmark::RegisterBenchmark(("Setup/P3/" + name).c_str(), setup<P3>)->Arg(long(i));
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
