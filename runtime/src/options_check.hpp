// Validation of erkn::Options: every field in its meaningful range, else erkn::Error naming it.
#pragma once

#include "erkn/integrator.hpp"

namespace erkn::detail {

void validate(const Options& options);

}  // namespace erkn::detail
