// The compensated update x += dx of the state (Options::compensated_summation): Kahan's
// summation, one definition for the implicit stepper and the MPI grid integrator. `error` carries
// the low-order bits of x lost in earlier updates and receives this one's; without it the
// round-off of q_n + dq grows like a random walk over the steps. (The explicit stepper folds the
// same update into its SIMD passes, explicit_stepper.hpp.)
#pragma once

namespace erkn::detail {

/// x += dx with the error of earlier updates added and this one's kept in `error`; dx is
/// clobbered. Works on any Eigen expressions of one size (vectors, arrays, maps). (Always inlined:
/// at d = 2 a call of its own took the implicit step's increments through memory.)
template <class X, class E, class D>
[[gnu::always_inline]] inline void compensated_add(X& x, E& error, D& dx) {
  dx += error;
  error = x;
  x += dx;
  error = (error - x) + dx;  // (the part of dx the rounded sum lost)
}

}  // namespace erkn::detail
