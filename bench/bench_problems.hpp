// The paper's problems P1 sine-Gordon (N = 32, circulant M), P2 Duffing (d = 1) and P3 stellar
// orbits (d = 2) (docs/design.md §4) for the benchmarks that put erkn beside the hand-written
// splitting peer (bench/splitting_peer.hpp): one gradient body for both, M, the initial state and
// the step size h; and the thread CPU timer both use.
#pragma once

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <erkn/erkn.hpp>
#include <numbers>
#include <vector>

#include "splitting_peer.hpp"
#include "thread_seconds.hpp"

namespace bench {

template <class F>
double seconds(F&& f) {
  const double start = thread_seconds();
  f();
  return thread_seconds() - start;
}

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
  static FourierBasis basis() { return FourierBasis(column().array()); }
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
  static DiagonalBasis<Vec> basis() { return {Vec::Constant(100)}; }
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
  static DiagonalBasis<Vec> basis() { return {Vec(4, 1)}; }
  static Eigen::VectorXd q0() { return Eigen::VectorXd::Ones(2); }
  static Eigen::VectorXd p0() { return Eigen::VectorXd::Zero(2); }
};

template <class P>
auto make_peer(const erkn::Method& m) {
  using Vec = typename P::Vec;
  const Vec q0 = P::q0().array(), p0 = P::p0().array();
  return SplittingPeer(m.table().c, m.table().d, m.stages(), P::h, P::basis(), &P::grad_peer, q0,
                       p0);
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

// CPU seconds of the timed loop shared by the per-evaluation benchmarks: batches of steps of
// erkn (plain and compensated) and of the peer, and the bare gradient at states along the
// trajectory (one per step of an untimed twin), so its inputs vary as they do in a run.
struct BatchTimes {
  double plain = 0, kahan = 0, peer = 0, grad = 0;
  static constexpr int kBatch = 256;
};

template <class P, class State, class Peer>
BatchTimes time_batches(State& state, erkn::Integrator& plain, erkn::Integrator& kahan, Peer& peer,
                        erkn::Integrator& twin) {
  BatchTimes t;
  std::vector<Eigen::VectorXd> states(BatchTimes::kBatch);
  Eigen::VectorXd g = P::q0();
  for (auto _ : state) {
    t.plain += seconds([&] {
      for (int k = 0; k < BatchTimes::kBatch; ++k) plain.step();
    });
    t.kahan += seconds([&] {
      for (int k = 0; k < BatchTimes::kBatch; ++k) kahan.step();
    });
    t.peer += seconds([&] {
      for (int k = 0; k < BatchTimes::kBatch; ++k) peer.step();
    });
    for (Eigen::VectorXd& q : states) twin.step(), q = twin.q();
    t.grad += seconds([&] {
      for (const Eigen::VectorXd& q : states) {
        P::grad(q, g);
        benchmark::DoNotOptimize(g.data());
      }
    });
  }
  return t;
}

}  // namespace bench
