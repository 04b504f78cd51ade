// The explicit path (abar_ii = 0: exact flows and kicks, FSAL when c_1 = 0 and c_s = 1) agrees
// with the generic stage-by-stage evaluation of eq. (d) to round-off, on every structure of M,
// for ERKN and RKN kinds; the registry's explicit methods are the splittings it assumes.
#include <gtest/gtest.h>

#include <string_view>

#include "problems.hpp"

namespace erkn::test {
namespace {

/// Nodes and weights of an explicit method; its coefficients follow from the symplectic
/// conditions with abar_ii = 0 (docs/design.md §1, the explicit family).
struct Splitting {
  const char* name;
  int s;
  double c[kMaxStages], d[kMaxStages];
};

const Splitting kSplittings[] = {
    {"Strang", 1, {0.5}, {1}},
    {"kick-flow-kick (FSAL)", 2, {0, 1}, {0.5, 0.5}},
    {"3 stages, FSAL", 3, {0, 0.6, 1}, {0.25, 0.5, 0.25}},
    {"3 stages, c not monotone", 3, {0.2, 0.9, 0.5}, {0.4, 0.3, 0.3}},
    // (c_s - c_1 = 1: the last flow of a step and the first of the next cancel, neither is 0)
    {"2 stages, flows 0 and s cancel", 2, {-0.25, 0.75}, {0.5, 0.5}},
};

const Splitting* current = nullptr;
double d_nudge = 0;  // added to d_1 in the table's coefficients (negative control)

void splitting_coefficients(double v, double* b, double* bbar, double* abar) {
  const Splitting& m = *current;
  auto phi0 = [](double w) { return std::cos(std::sqrt(w)); };
  auto phi1 = [](double w) { return w == 0 ? 1.0 : std::sin(std::sqrt(w)) / std::sqrt(w); };
  for (int i = 0; i < m.s; ++i) {
    const double di = m.d[i] + (i == 0 ? d_nudge : 0), e = 1 - m.c[i];
    b[i] = di * phi0(e * e * v);
    bbar[i] = di * e * phi1(e * e * v);
    for (int j = 0; j <= i; ++j) {
      const double dc = m.c[i] - m.c[j];
      abar[Coefficients::packed(i, j)] = (m.d[j] + (j == 0 ? d_nudge : 0)) * dc * phi1(dc * dc * v);
    }
  }
}

/// Two tables of one splitting: with abar_ii's closed form "0" (the explicit path) and with a
/// non-trivial spelling of zero (the generic path, whose stage solves then take one iteration).
struct Tables {
  generated::Table explicit_table, generic_table;
  const char* forms[3 * kMaxStages + Coefficients::kMaxPacked];
  const char* generic_forms[3 * kMaxStages + Coefficients::kMaxPacked];
};

Tables& tables_of(const Splitting& m, bool rkn) {
  static Tables t;
  current = &m;
  const int n = 2 * m.s + m.s * (m.s + 1) / 2;
  for (int k = 0; k < n; ++k) t.forms[k] = t.generic_forms[k] = "nonzero";
  for (int i = 0; i < m.s; ++i) {
    t.forms[2 * m.s + Coefficients::packed(i, i)] = "0";
    t.generic_forms[2 * m.s + Coefficients::packed(i, i)] = "0*v";
  }
  t.explicit_table = Method::all()[0].table();
  t.explicit_table.name = m.name;
  t.explicit_table.stages = m.s;
  t.explicit_table.rkn = rkn;
  t.explicit_table.c = m.c;
  t.explicit_table.d = m.d;
  t.explicit_table.coefficients = splitting_coefficients;
  t.explicit_table.poles = nullptr;
  t.explicit_table.npoles = 0;
  t.generic_table = t.explicit_table;
  t.explicit_table.closed_forms = t.forms;
  t.generic_table.closed_forms = t.generic_forms;
  return t;
}

std::vector<Stiffness> structures(int N) {
  const Stiffness circ = Stiffness::circulant(sine_gordon_column(N));
  return {Stiffness::scalar(50), Stiffness::diagonal(circ.to_dense(N).diagonal()), circ,
          Stiffness::dense(circ.to_dense(N))};
}

// Largest relative difference of (q, p) between the two paths over `steps` steps.
double path_difference(const Tables& t, const System& sys, double h, int steps, bool compensated,
                       const Eigen::VectorXd& q0, const Eigen::VectorXd& p0, long* evaluations) {
  Options o;
  o.compensated_summation = compensated;
  const MethodId id = Method::all()[0].id();
  Integrator fast(Method(id, &t.explicit_table), sys, h, q0, p0, o);
  Integrator generic(Method(id, &t.generic_table), sys, h, q0, p0, o);
  double worst = 0;
  for (int n = 0; n < steps; ++n) {
    fast.step();
    generic.step();
    const double scale = 1 + generic.q().norm() + generic.p().norm();
    worst = std::max(worst,
                     ((fast.q() - generic.q()).norm() + (fast.p() - generic.p()).norm()) / scale);
  }
  *evaluations = fast.statistics().gradient_evaluations;
  return worst;
}

TEST(ExplicitPath, AgreesWithTheGenericStagesToRoundOffOnEveryStructure) {
  const int N = 16, steps = 200;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(N, q0, p0);
  for (const Splitting& m : kSplittings)
    for (bool rkn : {false, true})
      for (const Stiffness& M : structures(N))
        for (bool compensated : {false, true}) {
          SCOPED_TRACE(std::string(m.name) + (rkn ? " RKN" : " ERKN") + " structure " +
                       std::to_string(int(M.structure())) + (compensated ? " Kahan" : ""));
          const Tables& t = tables_of(m, rkn);
          long evaluations = 0;
          const double h = rkn ? 0.01 : 1.0 / 40;
          EXPECT_LT(path_difference(t, sine_gordon(M), h, steps, compensated, q0, p0, &evaluations),
                    1e-12);
          // FSAL: the first kick of a step reuses the last gradient of the previous one.
          const bool fsal = m.s > 1 && m.c[0] == 0 && m.c[m.s - 1] == 1;
          EXPECT_EQ(evaluations, fsal ? 1 + steps * (m.s - 1) : steps * m.s);
        }
}

TEST(ExplicitPath, NegativeControlADifferentTableIsSeen) {
  // The same comparison with d_1 nudged in the table only (the explicit path reads d from the
  // nodes): the paths must then disagree far above the tolerance above.
  const int N = 16;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(N, q0, p0);
  for (const Splitting& m : kSplittings) {
    SCOPED_TRACE(m.name);
    const Tables& t = tables_of(m, false);
    d_nudge = 1e-6;
    long evaluations = 0;
    const double diff = path_difference(t, sine_gordon(Stiffness::circulant(sine_gordon_column(N))),
                                        1.0 / 40, 20, true, q0, p0, &evaluations);
    d_nudge = 0;
    EXPECT_GT(diff, 1e-9);
  }
}

TEST(ExplicitPath, RegistryMethodsWithZeroDiagonalAreTheSplittingOfTheirNodesAndWeights) {
  // The explicit path uses only c and d; the table must then be b_i = d_i phi0((1-c_i)^2 v),
  // bbar_i = d_i (1-c_i) phi1((1-c_i)^2 v), abar_ij = d_j (c_i-c_j) phi1((c_i-c_j)^2 v).
  int checked = 0;
  for (const Method& m : Method::all()) {
    const int s = m.stages();
    bool zero_diagonal = true;
    for (int i = 0; i < s; ++i)
      zero_diagonal &=
          std::string_view(m.table().closed_forms[2 * s + Coefficients::packed(i, i)]) == "0";
    if (!zero_diagonal) continue;
    ++checked;
    Splitting spec{m.table().name, s, {}, {}};
    for (int i = 0; i < s; ++i) spec.c[i] = m.table().c[i], spec.d[i] = m.table().d[i];
    current = &spec;
    for (double v : {0.0, 0.3, 2.0, 7.5}) {
      if (m.kind() == Kind::rkn && v > 0) continue;
      double b[kMaxStages], bbar[kMaxStages], abar[Coefficients::kMaxPacked];
      double b0[kMaxStages], bbar0[kMaxStages], abar0[Coefficients::kMaxPacked];
      m.table().coefficients(v, b, bbar, abar);
      splitting_coefficients(v, b0, bbar0, abar0);
      for (int i = 0; i < s; ++i) {
        EXPECT_NEAR(b[i], b0[i], 1e-13) << m.name() << " b" << i + 1 << " v = " << v;
        EXPECT_NEAR(bbar[i], bbar0[i], 1e-13) << m.name() << " bbar" << i + 1 << " v = " << v;
        for (int j = 0; j <= i; ++j)
          EXPECT_NEAR(abar[Coefficients::packed(i, j)], abar0[Coefficients::packed(i, j)], 1e-13)
              << m.name() << " abar" << i + 1 << j + 1 << " v = " << v;
      }
    }
  }
  RecordProperty("explicit_methods_checked", checked);
}

// The explicit stepper keeps the state one flow behind (the last flow of a step merged with the
// first of the next) and applies the pending flow only where the state is looked at. For every
// explicit registry method on each structure of M, q() and p() after every step agree to
// round-off with the unmerged path, forced by set_state after each step (it starts the next step
// without a pending flow); the negative control is the same comparison with h off by 1e-9.
double merged_difference(const Method& m, const Stiffness& M, int d, bool compensated, double dh) {
  const int steps = 40;
  Eigen::VectorXd q0, p0;
  sine_gordon_initial(d, q0, p0);
  Options o;
  o.compensated_summation = compensated;
  const double h = m.kind() == Kind::rkn ? 0.01 : 1.0 / 40;
  Integrator merged(m, sine_gordon(M), h, q0, p0, o);
  Integrator unmerged(m, sine_gordon(M), h * (1 + dh), q0, p0, o);
  double worst = 0;
  for (int n = 0; n < steps; ++n) {
    merged.step();
    unmerged.step();
    unmerged.set_state(Eigen::VectorXd(unmerged.q()), Eigen::VectorXd(unmerged.p()), unmerged.t());
    const double scale = 1 + unmerged.q().norm() + unmerged.p().norm();
    worst = std::max(
        worst, ((merged.q() - unmerged.q()).norm() + (merged.p() - unmerged.p()).norm()) / scale);
  }
  return worst;
}

TEST(ExplicitPath, MergedFlowsAcrossStepsGiveTheUnmergedStatesToRoundOff) {
  const int N = 16;
  // Every structure at d = N, and d = 3 with the identity basis (a compile-time dimension).
  std::vector<std::pair<Stiffness, int>> cases;
  for (const Stiffness& M : structures(N)) cases.emplace_back(M, N);
  cases.emplace_back(Stiffness::scalar(50), 3);
  cases.emplace_back(Stiffness::diagonal(Eigen::Vector3d(1, 50, 200)), 3);
  int checked = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit()) continue;
    ++checked;
    for (const auto& [M, d] : cases)
      for (bool compensated : {false, true}) {
        SCOPED_TRACE(std::string(m.name()) + " structure " + std::to_string(int(M.structure())) +
                     " d = " + std::to_string(d) + (compensated ? " Kahan" : ""));
        EXPECT_LT(merged_difference(m, M, d, compensated, 0), 1e-13);
        EXPECT_GT(merged_difference(m, M, d, compensated, 1e-9), 1e-11);  // (negative control)
      }
  }
  EXPECT_GT(checked, 0);
}

// Reading the state between steps (get_state: over arrays flow 0 backwards from the state, which
// runs ahead, into the second copy; the next step's staged Q kept, or staged anew where the read
// went through the staging buffer) leaves the trajectory bit for bit: every explicit method, every
// structure (the grids' transforms too: a periodic grid's half spectrum, a Dirichlet grid's r2r),
// plain and compensated. Negative control: runs set anew from what they read (then flow 0 is no
// longer merged) differ in some bits.
TEST(ExplicitPath, ReadingTheStateBetweenStepsLeavesTheTrajectoryBitForBit) {
  const int N = 16;
  using B = GridAxis::Boundary;
  std::vector<std::pair<Stiffness, int>> cases;
  for (const Stiffness& M : structures(N)) cases.emplace_back(M, N);
  cases.emplace_back(Stiffness::scalar(50), 3);
  cases.emplace_back(Stiffness::grid({{8, 0.5, B::periodic}, {6, 0.5, B::periodic}}), 48);
  cases.emplace_back(Stiffness::grid({{N, 0.5, B::dirichlet}}), N);
  int differing = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit()) continue;
    for (const auto& [M, d] : cases)
      for (bool compensated : {false, true}) {
        SCOPED_TRACE(std::string(m.name()) + " structure " + std::to_string(int(M.structure())) +
                     " d = " + std::to_string(d) + (compensated ? " Kahan" : ""));
        Eigen::VectorXd q0, p0;
        sine_gordon_initial(d, q0, p0);
        Options o;
        o.compensated_summation = compensated;
        const double h = m.kind() == Kind::rkn ? 0.01 : 1.0 / 40;
        auto run = [&] { return Integrator(m, sine_gordon(M), h, q0, p0, o); };
        Integrator read = run(), quiet = run(), reset = run();
        for (int n = 0; n < 12; ++n) {
          read.step(), quiet.step(), reset.step();
          EXPECT_TRUE(read.q().allFinite() && read.p().allFinite());
          reset.set_state(Eigen::VectorXd(reset.q()), Eigen::VectorXd(reset.p()), reset.t());
        }
        EXPECT_EQ(read.q(), quiet.q());
        EXPECT_EQ(read.p(), quiet.p());
        differing += reset.q() != quiet.q() || reset.p() != quiet.p();
      }
  }
  EXPECT_GT(differing, 0);
}

// Over arrays of more than 256 KiB a step of one pass overwrites its start where it cannot fail
// (explicit_stepper.hpp, in_place_steps): from a state with |p| < 2^600 and a force below it. The
// same problem from the state times 2^700 never steps in place (its p is too large), and with a
// linear force every value is that of the smaller run times 2^700 exactly: the runs agree bit
// for bit, every explicit method, a 1-D circulant, a periodic 256 x 256 grid (half spectra) and
// the identity basis, plain and compensated. Negative control: the run from a state 2^700 times
// larger but nudged in one entry differs.
TEST(ExplicitPath, StepsInPlaceGiveTheBitsOfStepsIntoTheSecondCopy) {
  using B = GridAxis::Boundary;
  const double scale = 0x1p700;
  const std::vector<Stiffness> large = {
      Stiffness::circulant(sine_gordon_column(1 << 16)),
      Stiffness::grid({{256, 1.0 / 256, B::periodic}, {256, 1.0 / 256, B::periodic}}),
      Stiffness::diagonal(Eigen::VectorXd::LinSpaced(1 << 16, 1, 1e4))};
  for (const Method& m : Method::all()) {
    if (!m.is_explicit()) continue;
    for (const Stiffness& M : large)
      for (bool compensated : {false, true}) {
        SCOPED_TRACE(std::string(m.name()) + " structure " + std::to_string(int(M.structure())) +
                     (compensated ? " Kahan" : ""));
        System s;
        s.M = M;
        s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = 0.75 * q; };
        s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                      Eigen::VectorXd& hv) { hv = 0.75 * v; };
        Options o;
        o.compensated_summation = compensated;
        o.blowup_guard = false;  // (its energy: 2^1400 overflows)
        const Eigen::Index d = M.dim();
        const Eigen::VectorXd q0 = Eigen::VectorXd::LinSpaced(d, 0, 6).array().sin();
        const Eigen::VectorXd p0 = Eigen::VectorXd::LinSpaced(d, 0, 5).array().cos();
        Eigen::VectorXd nudged = scale * q0;
        nudged[d / 3] *= 1 + 1e-15;
        Integrator small(m, s, 0.01, q0, p0, o), large_run(m, s, 0.01, scale * q0, scale * p0, o),
            control(m, s, 0.01, nudged, scale * p0, o);
        small.integrate(0.05), large_run.integrate(0.05), control.integrate(0.05);
        EXPECT_EQ(Eigen::VectorXd(scale * small.q()), large_run.q());
        EXPECT_EQ(Eigen::VectorXd(scale * small.p()), large_run.p());
        EXPECT_TRUE(control.q() != large_run.q() || control.p() != large_run.p());
      }
  }
}

}  // namespace
}  // namespace erkn::test
