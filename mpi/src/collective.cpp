#include "collective.hpp"

#include "erkn/error.hpp"

namespace erkn::mpi::detail {

void throw_if_any(MPI_Comm comm, const std::string& local_error) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int failing = local_error.empty() ? size : rank;
  MPI_Allreduce(MPI_IN_PLACE, &failing, 1, MPI_INT, MPI_MIN, comm);
  if (failing == size) return;
  std::string message = local_error;
  int length = int(message.size());
  MPI_Bcast(&length, 1, MPI_INT, failing, comm);
  message.resize(std::size_t(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, failing, comm);
  throw Error(size > 1 ? message + " (rank " + std::to_string(failing) + ")" : message);
}

}  // namespace erkn::mpi::detail
