// Coefficient tables of the splitting peers, from the literature. Conventions: A is the exact flow
// of the linear part (the "drift" of the papers, which integrate H = T(p) + V(q) with A = T), B the
// kick with grad U. Replacing the free flow by the harmonic one keeps every order condition used:
// with A = p'p/2 + q'Mq/2 and B = U(q), [B, [B, [B, A]]] = 0 still holds, the property the
// Runge-Kutta-Nystrom (SRKN) families exploit. Closing coefficients are recomputed from the
// consistency conditions (sum of kicks = sum of flows = 1) so they hold to the last bit.
#include <cmath>
#include <numeric>

#include "splitting.hpp"

namespace ex {
namespace {

/// Palindrome x_1 .. x_k, centre, x_k .. x_1 (centre omitted when `with_centre` is false).
std::vector<double> palindrome(const std::vector<double>& half, double centre, bool with_centre) {
  std::vector<double> out(half);
  if (with_centre) out.push_back(centre);
  out.insert(out.end(), half.rbegin(), half.rend());
  return out;
}

double sum(const std::vector<double>& x) { return std::accumulate(x.begin(), x.end(), 0.0); }

}  // namespace

Composition strang() {
  return {"Strang (impulse)",
          "Strang 1968; as the impulse method: Grubmüller et al. 1991, Tuckerman et al. 1992",
          2,
          {0.5, 0.5},
          {1.0},
          false,
          true,
          {},
          {}};
}

Composition blanes_moan_srkn6b() {
  // S. Blanes, P.C. Moan, Practical symplectic partitioned Runge-Kutta and Runge-Kutta-Nystrom
  // methods, J. Comput. Appl. Math. 142 (2002) 313-330, Table 3, SRKN_6^b (BAB, 6 stages):
  // b_1 a_1 b_2 a_2 b_3 a_3 b_4 a_3 b_3 a_2 b_2 a_1 b_1.
  const std::vector<double> a{0.245298957184271, 0.604872665711080};
  const std::vector<double> b{0.0829844064174052, 0.396309801498368, -0.0390563049223486};
  const double a3 = 0.5 - sum(a), b4 = 1 - 2 * sum(b);
  std::vector<double> flow_half = a;
  flow_half.push_back(a3);
  return {"Blanes–Moan SRKN6b",
          "Blanes & Moan, J. Comput. Appl. Math. 142 (2002), SRKN_6^b",
          4,
          palindrome(b, b4, true),
          palindrome(flow_half, 0, false),
          false,
          true,
          {},
          {}};
}

Composition blanes_moan_srkn14a() {
  // Blanes & Moan (2002), Table 3, SRKN_14^a (ABA, 14 stages, order 6):
  // a_1 b_1 a_2 ... b_6 a_7 b_7 a_8 b_7 a_7 b_6 ... b_1 a_1.
  const std::vector<double> a{0.0378593198406116,  0.102635633102435,  -0.0258678882665587,
                              0.314241403071447,   -0.130144459517415, 0.106417700369543,
                              -0.00879424312851058};
  std::vector<double> b{0.09171915262446165,  0.183983170005006, -0.05653436583288827,
                        0.004914688774712854, 0.143761127168358, 0.328567693746804};
  b.push_back(0.5 - sum(b));
  std::vector<double> kick{0.0};
  for (double x : palindrome(b, 0, false)) kick.push_back(x);
  kick.push_back(0.0);
  return {"Blanes–Moan SRKN14a",
          "Blanes & Moan, J. Comput. Appl. Math. 142 (2002), SRKN_14^a",
          6,
          kick,
          palindrome(a, 1 - 2 * sum(a), true),
          false,
          true,
          {},
          {}};
}

Composition aba1064() {
  // S. Blanes, F. Casas, A. Farres, J. Laskar, J. Makazaga, A. Murua, New families of symplectic
  // splitting methods for numerical integration in dynamical astronomy, Appl. Numer. Math. 68
  // (2013) 58-72, ABA(10,6,4): error O(eps h^10 + eps^2 h^6 + eps^3 h^4) for H = A + eps B.
  // a_1 b_1 a_2 b_2 a_3 b_3 a_4 b_4 a_5 b_4 a_4 b_3 a_3 b_2 a_2 b_1 a_1 (as in REBOUND's
  // integrator_saba.c).
  const std::vector<double> a{
      0.03809449742241219545697532230863756534060, 0.1452987161169137492940200726606637497442,
      0.2076276957255412507162056113249882065158, 0.4359097036515261592231548624010651844006};
  std::vector<double> b{0.09585888083707521061077150377145884776921,
                        0.2044461531429987806805077839164344779763,
                        0.2170703479789911017143385924306336714532};
  b.push_back(0.5 - sum(b));
  std::vector<double> kick{0.0};
  for (double x : palindrome(b, 0, false)) kick.push_back(x);
  kick.push_back(0.0);
  return {"ABA(10,6,4)",
          "Blanes, Casas, Farrés, Laskar, Makazaga & Murua, Appl. Numer. Math. 68 (2013)",
          4,
          kick,
          palindrome(a, 1 - 2 * sum(a), true),
          false,
          false,
          {},
          {}};
}

Composition mollified_impulse() {
  // B. Garcia-Archilla, J.M. Sanz-Serna, R.D. Skeel, Long-time-step methods for oscillatory
  // differential equations, SIAM J. Sci. Comput. 20 (1999) 930-963; with the filter
  // phi = sinc, psi = sinc phi: Hairer, Lubich & Wanner, Geometric Numerical Integration (2006),
  // Sec. XIII.2.2, method (C). Strang splitting of H with U(q) replaced by U(Phi q): symplectic.
  Composition c = strang();
  c.name = "mollified impulse (sinc)";
  c.source =
      "García-Archilla, Sanz-Serna & Skeel, SIAM J. Sci. Comput. 20 (1999); GNI XIII.2.2 (C)";
  c.filtered = true;
  c.for_grids = false;  // built for near-integrable and resonant problems (P1-P3 charts)
  return c;
}

Composition omf4_3f3g() {
  // I.P. Omelyan, I.M. Mryglod, R. Folk, Symplectic analytically integrable decomposition
  // algorithms, Comput. Phys. Commun. 151 (2003) 272-314, eqs. (40)-(42), 4MN3F3GP (minimum
  // norm, 3 forces, 3 force gradients, position version); lambda, chi and the formulas for theta
  // and xi as in jxy/MDevolve src/mdevolve.nim (mkOmelyan4MN3F3GP) @
  // 2d2f4d586419049d2fdb1fbb762afc1c55d02fa1:
  // T(theta) V(lambda) G(xi) T(1/2-theta) V(1-2 lambda) G(chi) T(1/2-theta) G(xi) V(lambda)
  // T(theta). Its G step of weight xi is p += xi h^3 grad |grad U|^2, so e = -xi here.
  const double lambda = 0.2825633404177051, chi = 0.003035236056708454;
  const double theta = 0.5 - 1.0 / std::sqrt(24.0 * lambda);
  const double xi = (1.0 - 12.0 * chi - std::sqrt(6.0 * lambda) * (1.0 - lambda)) / 24.0;
  Composition c{"OMF4 (4MN3F3GP)",
                "Omelyan, Mryglod & Folk, Comput. Phys. Commun. 151 (2003), 4MN3F3GP",
                4,
                {0, lambda, 1 - 2 * lambda, lambda, 0},
                {theta, 0.5 - theta, 0.5 - theta, theta},
                false,
                true,
                {0, -xi, -chi, -xi, 0},
                {}};
  return c;
}

Composition pmlf6() {
  // S. Blanes, F. Casas, J. Ros, Symplectic integration with processing: a general study,
  // SIAM J. Sci. Comput. 21 (1999) 711-727; as REBOUND's EOS method PMLF6 (hannorein/rebound
  // src/integrator_eos.c @ 0c7d40c89524e48cdbaa0f38c10a798f7c2b9798: pmlf6_a, _b, _c for the
  // kernel, pmlf6_z, _y, _v for the processor). Kernel: A(a0) B(b0, c0) A(a1) B(b1, c1) A(a1)
  // B(b0, c0) A(a0); its preprocessor (pi^-1 here): A(z_i) B(y_i, v_i), i = 0..5; its
  // postprocessor is the reverse with every coefficient negated. REBOUND's kick B(y, v) is
  // p += y a + v grad |a|^2 with a = -grad U (v already carries h^3), so e = -c and e = -v here.
  const std::vector<double> a{-0.0682610383918630, 0.568261038391863038121699};
  const std::vector<double> b{0.2621129352517028, 0.475774129496594366806050};
  const std::vector<double> c{0., 0.0164011128160783};
  const std::vector<double> z{0.07943288242455420, 0.02974829169467665, -0.7057074964815896,
                              0.3190423451260838,  -0.2869147334299646, 0.564398710666239478150885};
  const std::vector<double> y{1.3599424487455264,    -0.6505973747535132,
                              -0.033542814598338416, -0.040129915275115030,
                              0.044579729809902803,  -0.680252073928462652752103};
  const std::vector<double> v{-0.034841228074994859,
                              0.031675672097525204,
                              -0.005661054677711889,
                              0.004262222269023640,
                              0.005,
                              -0.005};
  Composition k{"PMLF6 (processed)",
                "Blanes, Casas & Ros, SIAM J. Sci. Comput. 21 (1999); REBOUND's EOS PMLF6",
                6,
                {0, b[0], b[1], b[0], 0},
                {a[0], a[1], a[1], a[0]},
                false,
                true,
                {0, -c[0], -c[1], -c[0], 0},
                {z, y, {}}};
  for (double x : v) k.processor.modified.push_back(-x);
  return k;
}

int evaluations_per_step(const Composition& c) {
  int n = 0;
  for (double b : c.kick) n += b != 0;
  return c.kick.front() != 0 && c.kick.back() != 0 ? n - 1 : n;
}

}  // namespace ex
