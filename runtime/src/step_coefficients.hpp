// The coefficients of one step, evaluated once per (h, M) at every eigenvalue of M and scaled by
// the powers of h they appear with. Coef is double (one eigenvalue: scalar M, RKN methods) or an
// array over the eigen coordinates.
#pragma once

#include <Eigen/Core>
#include <array>

#include "erkn/method.hpp"
#include "phi.hpp"

namespace erkn::detail {

template <class Coef>
struct StepCoefficients {
  int s = 0;
  std::array<Coef, kMaxStages> phi0c;                        ///< phi0(c_i^2 V)
  std::array<Coef, kMaxStages> hcphi1c;                      ///< h c_i phi1(c_i^2 V)
  std::array<Coef, kMaxStages*(kMaxStages + 1) / 2> h2abar;  ///< h^2 abar_ij(V), packed
  std::array<Coef, kMaxStages> h2bbar;                       ///< h^2 bbar_i(V)
  std::array<Coef, kMaxStages> hb;                           ///< h b_i(V)
  Coef phi0m1;                                               ///< phi0(V) - 1
  Coef hphi1;                                                ///< h phi1(V)
  Coef mhMphi1;                                              ///< -h M phi1(V) = -(V/h) phi1(V)
  const Coef& abar(int i, int j) const { return h2abar[i * (i + 1) / 2 + j]; }
};

inline void resize_coef(double&, Eigen::Index) {}
inline void resize_coef(Eigen::ArrayXd& c, Eigen::Index m) { c.resize(m); }
inline void set_coef(double& c, Eigen::Index, double x) { c = x; }
inline void set_coef(Eigen::ArrayXd& c, Eigen::Index k, double x) { c[k] = x; }

/// v_k = h^2 lambda_k; lambda must have one entry when Coef is double. The caller has checked
/// every v against the method's poles (check_step_size), so the table is evaluated directly.
/// Only the s stages' coefficients are sized.
template <class Coef>
StepCoefficients<Coef> step_coefficients(const Method& method, double h,
                                         const Eigen::VectorXd& lambda) {
  StepCoefficients<Coef> k;
  k.s = method.stages();
  const Eigen::Index m = lambda.size();
  for (int i = 0; i < k.s; ++i) {
    for (auto* arr : {&k.phi0c, &k.hcphi1c, &k.h2bbar, &k.hb}) resize_coef((*arr)[i], m);
    for (int j = 0; j <= i; ++j) resize_coef(k.h2abar[i * (i + 1) / 2 + j], m);
  }
  for (Coef* c : {&k.phi0m1, &k.hphi1, &k.mhMphi1}) resize_coef(*c, m);
  const generated::Table& table = method.table();
  Coefficients co;
  for (Eigen::Index e = 0; e < m; ++e) {
    const double v = h * h * lambda[e];
    table.coefficients(v, co.b.data(), co.bbar.data(), co.abar_packed.data());
    for (int i = 0; i < k.s; ++i) {
      const double c = table.c[i];
      set_coef(k.phi0c[i], e, phi0(c * c * v));
      set_coef(k.hcphi1c[i], e, h * c * phi1(c * c * v));
      set_coef(k.h2bbar[i], e, h * h * co.bbar[i]);
      set_coef(k.hb[i], e, h * co.b[i]);
      for (int j = 0; j <= i; ++j)
        set_coef(k.h2abar[i * (i + 1) / 2 + j], e, h * h * co.abar(i, j));
    }
    set_coef(k.phi0m1, e, phi0_minus_1(v));
    set_coef(k.hphi1, e, h * phi1(v));
    set_coef(k.mhMphi1, e, -h * lambda[e] * phi1(v));
  }
  return k;
}

}  // namespace erkn::detail
