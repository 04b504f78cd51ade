// The process's pool of large blocks (block_pool.hpp): a few given-back blocks, found by their
// exact size, under a mutex (ensembles construct and drop Integrators on several threads).
//
// The first block of each size given back is freed, not kept: glibc's malloc then learns its size
// (the mmap threshold rises to it, the trim threshold to twice it) as it did before the pool, and
// the run's other blocks (FlowCoefficients', the transforms' buffers, the Eigen vectors of the
// Integrator and its stepper) stay below the trim threshold. A pool keeping every block left
// glibc's thresholds at their defaults (128 KB) and those blocks were trimmed after every run at
// N = 4096 and 8192 instead (116 and 163 brk calls in 50 runs, against 15 and 14 before).
#include "block_pool.hpp"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

namespace erkn::detail {
namespace {

// At most this many free blocks and bytes are kept: the blocks of a few Integrators alive at once
// (an ensemble's threads), not of every size a process ever used.
constexpr std::size_t kKeptBlocks = 16;
constexpr std::size_t kKeptBytes = std::size_t(256) << 20;
// At most this many sizes are remembered as given back once; the oldest is forgotten for a new one
// (a size given back again after that is freed once more: glibc relearns it, nothing is lost).
constexpr std::size_t kSeenSizes = 64;

struct Pool {
  std::mutex mutex;
  std::vector<std::pair<std::size_t, void*>> free;  // (bytes, block)
  std::vector<std::size_t> seen;                    // the sizes given back once
  std::size_t bytes = 0;
};

// Never destroyed: an Integrator that outlives the process's static destructors (one held by a
// static object built before the pool) still gives its block back to a live pool; the blocks kept
// at exit go with the process.
Pool& pool() {
  static Pool* p = new Pool;
  return *p;
}

// The block this thread keeps (take_kept_block): trivially destructible, so that reading it needs
// no initialisation guard, and still readable when an Integrator is destroyed after the thread's
// destructors ran (a thread_local or static one): its block is then freed (closed).
struct Kept {
  void* block;
  std::size_t bytes;
  bool closed;
};
thread_local Kept kept{};
// The vectors this thread keeps (take_kept_vectors), in raw storage for the same reason:
// constructed by the first give_kept_vectors, destroyed when the thread ends.
constexpr int kKeptVectors = 2;
struct KeptVectors {
  alignas(Eigen::VectorXd) unsigned char bytes[kKeptVectors][sizeof(Eigen::VectorXd)];
  bool constructed;
  Eigen::VectorXd& operator[](int k) {
    return *std::launder(reinterpret_cast<Eigen::VectorXd*>(bytes[k]));
  }
};
thread_local KeptVectors kept_vectors{};
// Frees the kept block and vectors when the thread ends (set up by the first one kept).
struct KeptRelease {
  bool armed = false;
  ~KeptRelease() {
    std::free(kept.block);
    kept = {nullptr, 0, true};
    if (kept_vectors.constructed)
      for (int k = 0; k < kKeptVectors; ++k) kept_vectors[k].~Matrix();
    kept_vectors.constructed = false;
  }
};
thread_local KeptRelease kept_release;

}  // namespace

void* take_kept_block(std::size_t bytes) {
  if (kept.block && kept.bytes == bytes) return std::exchange(kept.block, nullptr);
  void* block = std::malloc(bytes);
  if (!block) throw std::bad_alloc();
  return block;
}

void give_kept_block(void* block, std::size_t bytes) noexcept {
  if (kept.closed) return std::free(block);
  std::free(kept.block);      // (the newest kept: the size the thread's next stepper likely has)
  kept_release.armed = true;  // (its destructor registered with the thread's first use)
  kept = {block, bytes, false};
}

void take_kept_vectors(Eigen::Index n, Eigen::VectorXd& a, Eigen::VectorXd& b) {
  if (kept_vectors.constructed && kept_vectors[0].size() == n && kept_vectors[1].size() == n) {
    a.swap(kept_vectors[0]);  // (the storages exchanged: no allocation)
    b.swap(kept_vectors[1]);
  } else {
    a.resize(n);
    b.resize(n);
  }
}

void give_kept_vectors(Eigen::VectorXd& a, Eigen::VectorXd& b) noexcept {
  // (Large ones not: their malloc is small against a step, and a thread that builds no more
  // stepper would hold them.)
  if (kept.closed || std::size_t(a.size() + b.size()) * sizeof(double) >= kPooledBytes) return;
  if (!kept_vectors.constructed) {
    for (int k = 0; k < kKeptVectors; ++k) new (kept_vectors.bytes[k]) Eigen::VectorXd();
    kept_vectors.constructed = true;
    kept_release.armed = true;  // (its destructor registered with the thread's first use)
  }
  kept_vectors[0].swap(a);
  kept_vectors[1].swap(b);
}

void* take_block(std::size_t bytes) {
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    for (auto it = p.free.begin(); it != p.free.end(); ++it)
      if (it->first == bytes) {
        void* block = it->second;
        p.bytes -= bytes;
        p.free.erase(it);
        return block;
      }
  }
  // (A cache line: at least Eigen's AlignedMax under any compiler flags of the including code.)
  const std::size_t line = 64, rounded = (bytes + line - 1) / line * line;
  void* block = std::aligned_alloc(line, rounded);
  if (!block) throw std::bad_alloc();
  return block;
}

void give_block(void* block, std::size_t bytes) noexcept {
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    try {  // (no room for an entry: the block is freed)
      if (std::find(p.seen.begin(), p.seen.end(), bytes) == p.seen.end()) {
        if (p.seen.size() == kSeenSizes) p.seen.erase(p.seen.begin());
        p.seen.push_back(bytes);  // (the first of its size: freed, see above)
      } else if (p.free.size() < kKeptBlocks && p.bytes + bytes <= kKeptBytes) {
        p.free.emplace_back(bytes, block);
        p.bytes += bytes;
        return;
      }
    } catch (...) {
    }
  }
  std::free(block);
}

}  // namespace erkn::detail
