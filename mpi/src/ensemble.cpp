// An ensemble over ranks: contiguous blocks of trajectories per rank, then every result to every
// rank (serialised into bytes, one MPI_Allgatherv).
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "collective.hpp"
#include "erkn/mpi.hpp"

namespace erkn::mpi {
namespace {

class Writer {
 public:
  template <class T>
  void put(const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&x);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void put(const Eigen::VectorXd& v) {
    put(std::int64_t(v.size()));
    const char* p = reinterpret_cast<const char*>(v.data());
    bytes.insert(bytes.end(), p, p + sizeof(double) * std::size_t(v.size()));
  }
  void put(const std::string& s) {
    put(std::int64_t(s.size()));
    bytes.insert(bytes.end(), s.begin(), s.end());
  }
  std::vector<char> bytes;
};

class Reader {
 public:
  explicit Reader(const char* p) : p_(p) {}
  template <class T>
  void get(T& x) {
    std::memcpy(&x, p_, sizeof(T));
    p_ += sizeof(T);
  }
  void get(Eigen::VectorXd& v) {
    std::int64_t n;
    get(n);
    v.resize(Eigen::Index(n));
    std::memcpy(v.data(), p_, sizeof(double) * std::size_t(n));
    p_ += sizeof(double) * std::size_t(n);
  }
  void get(std::string& s) {
    std::int64_t n;
    get(n);
    s.assign(p_, std::size_t(n));
    p_ += n;
  }

 private:
  const char* p_;
};

void put(Writer& w, const TrajectoryResult& r) {
  w.put(r.q), w.put(r.p), w.put(r.t), w.put(r.statistics), w.put(r.error);
}

void get(Reader& in, TrajectoryResult& r) {
  in.get(r.q), in.get(r.p), in.get(r.t), in.get(r.statistics), in.get(r.error);
}

}  // namespace

std::vector<TrajectoryResult> integrate(MPI_Comm comm, const Ensemble& ensemble, double t_end,
                                        int threads) {
  int rank = 0, size = 1;  // (this rank's block: trajectories first(rank)..first(rank + 1) - 1)
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const std::size_t n = ensemble.size();
  const auto first = [&](int r) { return n * std::size_t(r) / std::size_t(size); };
  // (Its only errors are bad arguments, the same on every rank.)
  const std::vector<TrajectoryResult> mine =
      ensemble.integrate(t_end, first(rank), first(rank + 1), threads);
  Writer w;
  for (const TrajectoryResult& r : mine) put(w, r);
  const std::vector<char> all =
      detail::all_gather(comm, w.bytes.data(), int(w.bytes.size()), MPI_CHAR);
  std::vector<TrajectoryResult> results(n);
  Reader in(all.data());
  for (TrajectoryResult& r : results) get(in, r);
  return results;
}

}  // namespace erkn::mpi
