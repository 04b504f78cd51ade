// The experiments' names for the shared problems library (problems/, erkn::problems).
#pragma once

#include <erkn/problems.hpp>
#include <erkn/problems/reference.hpp>

namespace ex {

using erkn::problems::duffing;
using erkn::problems::GridAxis;
using erkn::problems::LinearPart;
using erkn::problems::Precision;
using erkn::problems::Problem;
using erkn::problems::problem_by_key;
using erkn::problems::Reference;
using erkn::problems::reference_solution;
using erkn::problems::sine_gordon;
using erkn::problems::stellar_orbits;
using erkn::problems::Vec;
using erkn::problems::VecLD;

}  // namespace ex
