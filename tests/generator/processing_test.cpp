// Processed methods psi = pi o K o pi^-1 (processing.hpp): the effective order is certified on
// the composition pi^-1, K, pi; the kernel's own order is reported beside it.
#include "processing.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "certify.hpp"
#include "derive.hpp"
#include "spec.hpp"

namespace erkn::gen {
namespace {

MethodSpec spec_of(const std::string& text) {
  std::istringstream in(text);
  return read_specs(in).at(0);
}

// PLF7_6_4 as in methods.spec (REBOUND's digits): kernel and processor, each a line.
const std::string kKernel =
    "method P\nkind explicit\nsource test\nstages 3\norder 4\ngeneralized 7, 6, 4\n"
    "drift 0.5600879810924619, -0.060087981092461900000, -0.060087981092461900000, "
    "0.5600879810924619\nkick 1.5171479707207228, -2.0342959414414456000, 1.5171479707207228\n";
const std::string kDrifts =
    "pre_drift -0.3346222298730800, 1.0975679907321640, -1.0380887460967830, "
    "0.6234776317921379, -1.1027532063031910, -0.0141183222088869\n";
const std::string kKicks =
    "pre_kick -1.6218101180868010, 0.0061709468110142, 0.8348493592472594, -0.0511253369989315, "
    "0.5633782670698199, -0.5\n";

TEST(Processing, PublishedDigitsCertifyTheEffectiveOrderAndTheKernelsOwn) {
  const Derived m = derive(spec_of(kKernel + kDrifts + kKicks));
  EXPECT_EQ(m.certificate.order, 4);
  EXPECT_EQ(m.certificate.generalized.at(0), 7);
  EXPECT_EQ(m.certificate.generalized.at(1), 6);
  EXPECT_EQ(m.certificate.generalized.at(2), 4);
  // The kernel alone is a second-order splitting: processing is what the order comes from.
  EXPECT_EQ(m.kernel_certificate.order, 2);
  EXPECT_LT(m.kernel_certificate.generalized.at(0), 7);
  ASSERT_EQ(m.pre.kick.size(), 6u);
}

// Negative controls: a wrong digit (1e-6, beyond rounding) fails at a named tree; the kernel
// alone cannot claim the processed orders.
TEST(Processing, AWrongDigitOrNoProcessorFailsAtANamedTree) {
  const std::string wrong =
      "pre_kick -1.6218101180868010, 0.0061709468110142, 0.8348493592472594, "
      "-0.0511263369989315, 0.5633782670698199, -0.5\n";
  for (const std::string& bad : {kKernel + kDrifts + wrong, kKernel}) {
    try {
      derive(spec_of(bad));
      ADD_FAILURE() << "accepted:\n" << bad;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("tree f"), std::string::npos) << e.what();
    }
  }
}

// pi must be the exact inverse of pi^-1 (reversed, coefficients negated): with its kicks not
// negated the composition certifies no more than the kernel's order.
TEST(Processing, OnlyTheInverseProcessorGivesTheEffectiveOrder) {
  const Derived m = derive(spec_of(kKernel + kDrifts + kKicks));
  const KickSequence psi = composition(m.c, m.d, m.e, m.pre);
  const int n = int(m.pre.kick.size()), s = m.stages();
  EXPECT_EQ(int(psi.c.size()), 2 * n + s);
  EXPECT_EQ(certify(explicit_series(psi.c, psi.d, 5), false, 8).order, 4);
  KickSequence adjoint = psi;
  for (int k = 0; k < n; ++k) adjoint.d[n + s + k] = -adjoint.d[n + s + k];
  EXPECT_LE(certify(explicit_series(adjoint.c, adjoint.d, 5), false, 8).order, 2);
}

TEST(Processing, SpecRefusesWhatItCannotMean) {
  EXPECT_EQ(spec_of(kKernel + kDrifts + kKicks).pre_drift.size(), 6u);
  const std::string implicit_kernel =
      "method C\nsource t\nstages 1\norder 2\nc 1/2\nd 1\nrkn R\ndiagonal abar11 == 0\n";
  for (const std::string& bad :
       {kKernel + kKicks,                                         // no drifts
        kKernel + "pre_drift 0, 1, 2, 3, 4, 5, 6, 7\n" + kKicks,  // too many drifts
        kKernel + kDrifts + kKicks + "pre_modified 0, 0\n",       // one per kick
        kKernel + kDrifts,                                        // drifts without kicks
        implicit_kernel + "pre_drift 0\npre_kick 1\n"}) {         // kind erkn
    EXPECT_THROW(spec_of(bad), std::runtime_error) << bad;
  }
}

}  // namespace
}  // namespace erkn::gen
