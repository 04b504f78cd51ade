// Exact-flow splitting peers: compositions of the exact flow of q'' + Mq = 0 (computed in M's
// eigen coordinates) with kicks p -= h b_i grad U(q), the strongest explicit competitors of the
// ERKN methods (docs/design.md §1, "the explicit family"). Written independently of the runtime:
// own coefficient tables, own linear flow, the problem's own grad U.
#pragma once

#include <string>
#include <vector>

#include "solver.hpp"

namespace ex {

/// Processing psi = pi o K o pi^-1 (the composition is the kernel K): pi^-1 = exp(h z_0 A)
/// exp(h y_0 B_0) exp(h z_1 A) exp(h y_1 B_1) ..., B_i a (modified) kick with weights y_i and
/// modified[i]. The peer applies pi^-1 once to the initial state and pi (the reverse sequence,
/// every coefficient negated) to each state it gives out, never to the state it steps.
struct Processor {
  std::vector<double> flow, kick, modified;  ///< z_i, y_i, e_i (same sizes; empty: none)
};

/// exp(h b_0 B) exp(h a_1 A) exp(h b_1 B) ... exp(h a_m A) exp(h b_m B), A the linear flow, B the
/// kick; kick.size() == flow.size() + 1, zero kicks are skipped. When b_0 and b_m are both non-zero
/// the last kick of a step and the first of the next share one evaluation (FSAL).
/// A modified kick (force-gradient) is p -= h b_i grad U + h^3 e_i G, G = grad(|grad U|^2) =
/// 2 Hess U grad U (Problem::hessian_vector_u), at the same q; it counts as one evaluation of
/// grad U, as the runtime's Statistics::gradient_evaluations does.
struct Composition {
  std::string name;
  std::string source;  ///< citation of the coefficients
  int order = 0;
  std::vector<double> kick, flow;
  /// Mollified kicks: grad U(q) replaced by Phi grad U(Phi q), Phi = sinc(h Omega), Omega =
  /// M^{1/2}.
  bool filtered = false;
  /// Run in the large-grid scenes (Solver::suits_grid).
  bool for_grids = false;
  std::vector<double> modified;  ///< e_i per kick (kick.size() entries; empty: plain kicks)
  Processor processor;           ///< empty: not processed
};

Composition strang();               ///< Strang / impulse, order 2
Composition blanes_moan_srkn6b();   ///< Blanes & Moan 2002, SRKN_6^b, order 4
Composition blanes_moan_srkn14a();  ///< Blanes & Moan 2002, SRKN_14^a, order 6
Composition aba1064();              ///< Blanes et al. 2013, ABA(10,6,4), order 4 (10, 6, 4 in eps)
Composition mollified_impulse();    ///< Garcia-Archilla, Sanz-Serna & Skeel 1999, sinc filter
Composition omf4_3f3g();  ///< Omelyan, Mryglod & Folk 2003, 4MN3F3GP: order 4, force-gradient
Composition pmlf6();      ///< Blanes, Casas & Ros 1999 (REBOUND's PMLF6): processed, order 6

/// The compositions of make_splitting_peers, in its order.
std::vector<Composition> splitting_peer_compositions();

/// Kicks (evaluations of grad U) per step, after FSAL.
int evaluations_per_step(const Composition& c);

std::unique_ptr<Solver> make_splitting(Composition composition);

}  // namespace ex
