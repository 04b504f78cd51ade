// The phi-functions of eq. (e) as a GiNaC function phi(j, x) = sum_k (-1)^k x^k / (2k+j)!,
// with exact series, numeric evaluation and derivative, so that closed forms printed by the
// generator (GiNaC syntax) can be read back, expanded and evaluated by the symbolic tests.
#pragma once

#include <ginac/ginac.h>

namespace erkn::gen {

DECLARE_FUNCTION_2P(phi)

/// A GiNaC parser that knows phi and the symbol v.
GiNaC::parser make_parser(const GiNaC::symbol& v);

}  // namespace erkn::gen
