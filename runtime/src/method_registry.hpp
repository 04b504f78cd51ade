// What Method::add and Method::load share: the checks before a table joins the registry.
#pragma once

#include <span>

#include "erkn/table.hpp"

namespace erkn::detail {

/// Throws erkn::Error naming the problem when `table` cannot be added (Method::add's list).
void check_addable(const generated::Table& table, std::span<const double> modified);

}  // namespace erkn::detail
