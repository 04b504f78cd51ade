#include "solver.hpp"
#include "splitting.hpp"

namespace ex {

SolverList all_solvers() {
  SolverList list = make_erkn_solvers();
  list.push_back(make_stormer_verlet());
  list.push_back(make_mclachlan_sb3a());
  list.push_back(make_mclachlan_sb3a_m4());
  list.push_back(make_gauss2());
  for (auto& s : make_splitting_peers()) list.push_back(std::move(s));
  return list;
}

}  // namespace ex
