// What Method::add and Method::load share: the checks before a table joins the registry.
#pragma once

#include "erkn/table.hpp"

namespace erkn::detail {

/// Throws erkn::Error naming the problem when `table` cannot be added (Method::add's list).
void check_addable(const generated::Table& table);

/// b[s], bbar[s], abar[s(s+1)/2] of the explicit family (exact linear flow and kicks with
/// weights d) at v: Method::evaluate for explicit methods given as data, and the stability
/// matrix of modified kicks (with d = 1: the coefficients per unit weight).
void explicit_family(const double* c, const double* d, int s, double v, double* b, double* bbar,
                     double* abar);

}  // namespace erkn::detail
