// erkn-mpi's scaling table (tab-separated rows, one per run) and the markdown report with the
// model of the all-to-all cost beyond the ranks measured.
#pragma once

#include <ostream>
#include <string>

#include "scene.hpp"

namespace erkn::mpi::report {

/// Bytes all ranks send in all-to-alls per step: each transform moves the (P-1)/P of the d
/// doubles that change owner.
inline double alltoall_bytes(double d, int ranks, double transforms_per_step) {
  return transforms_per_step * 8 * d * double(ranks - 1) / double(ranks);
}

void append(std::ostream& table, const std::string& kind, const std::string& grid,
            const std::string& method, const scene::Timing& t);

/// Reads the table and writes the markdown report (the last row of each kind and rank count).
void write(const std::string& table, const std::string& markdown);

}  // namespace erkn::mpi::report
