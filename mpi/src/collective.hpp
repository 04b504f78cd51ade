// Errors that every rank agrees on: a check that fails on some ranks is thrown on all of them,
// with the message of the lowest failing rank, so no rank is left waiting in a collective call.
#pragma once

#include <mpi.h>

#include <exception>
#include <string>
#include <vector>

namespace erkn::mpi::detail {

/// Collective. Throws erkn::Error(message of the lowest rank whose local_error is non-empty)
/// on every rank; returns if every local_error is empty.
void throw_if_any(MPI_Comm comm, const std::string& local_error);

/// An exception's message without erkn::Error's prefix "erkn: " (Error adds it again).
inline std::string message_of(const std::exception& e) {
  std::string message = e.what();
  if (message.rfind("erkn: ", 0) == 0) message.erase(0, 6);
  return message;
}

/// Runs f() and turns an exception on any rank into the same erkn::Error on every rank.
template <class F>
void collectively(MPI_Comm comm, F&& f) {
  std::string error;
  try {
    f();
  } catch (const std::exception& e) {
    error = message_of(e);
  }
  throw_if_any(comm, error);
}

/// The n items at data of every rank, concatenated in rank order, on every rank.
template <class T>
std::vector<T> all_gather(MPI_Comm comm, const T* data, int n, MPI_Datatype type) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(counts.size(), 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<T> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(data, n, type, all.data(), counts.data(), offsets.data(), type, comm);
  return all;
}

}  // namespace erkn::mpi::detail
