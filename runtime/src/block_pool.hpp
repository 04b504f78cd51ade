// Large per-Integrator blocks kept for the next Integrator of the process (issue 17): the explicit
// stepper's arrays (10 state-sized arrays: 164 KB at sine-Gordon N = 2048) were allocated with
// every construction and freed with every Integrator. Under glibc's default malloc settings a
// user's loop of construct + integrate then had the heap trimmed after every run and its pages
// faulted back in the next: the first such block, mmap'ed and freed, raises glibc's mmap threshold
// to its size and the trim threshold to twice that, and the run's blocks, coalesced into the
// heap's top when the Integrator is freed, reached the latter (user-like driver, FFTW wisdom from
// a file, N = 2048 Strang: 2 brk calls per run, 12 % of the samples in the kernel; N = 1024 and
// 1536 likewise; N = 512, 4096 and 8192 not). Blocks below kPooledBytes stay with Eigen's
// allocator, as before (malloc: its per-thread caches serve them, allocation_test.cpp).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <utility>

namespace erkn::detail {

/// Blocks of at least this many bytes go through the pool.
inline constexpr std::size_t kPooledBytes = std::size_t(32) << 10;

/// A block of `bytes` (>= kPooledBytes) from the pool (one given back earlier, of exactly that
/// size) or new; aligned to 64 bytes; uninitialised.
void* take_block(std::size_t bytes);
/// Gives back a block of take_block(bytes): kept for a later take_block (a few blocks: the
/// process's Integrators alive at once) or freed.
void give_block(void* block, std::size_t bytes) noexcept;

/// A block of `bytes` (below kPooledBytes, at most __STDCPP_DEFAULT_NEW_ALIGNMENT__-aligned
/// objects): the one this thread gave back last when of that size, else malloc's; uninitialised.
/// For the implicit stepper (stepper.hpp), ~10.8 KB at D = 2: above the 1,032 bytes that
/// glibc's per-thread cache serves, so each construction took _int_malloc and each destruction
/// _int_free (and, with fastbins, malloc_consolidate).
void* take_kept_block(std::size_t bytes);
/// Gives back a block of take_kept_block(bytes): kept for this thread's next take_kept_block in
/// place of the one kept before, which is freed (a thread's kept block is freed when it ends).
void give_kept_block(void* block, std::size_t bytes) noexcept;

/// The stage solver's two vectors that the user's callbacks see (its iterate Q and gradient g:
/// Eigen::VectorXd, their own allocations), kept per thread like the implicit stepper's block: a
/// malloc and a free each per construction were ~260 of the ~6,600 instructions of a construct +
/// 1-step run of SERKN2s3 at P3 (callgrind; a call per vector to take and give one cost ~110 of
/// them). a, b (empty) take the two vectors this thread gave back last when they have n entries
/// (their values those they had), else new ones of n entries (uninitialised).
void take_kept_vectors(Eigen::Index n, Eigen::VectorXd& a, Eigen::VectorXd& b);
/// Keeps the storage of a and b for this thread's next take_kept_vectors; a and b then hold the
/// storage kept before (or none), which their owner frees (a thread's kept vectors are freed
/// when it ends; after that, and when a and b together reach kPooledBytes, a and b are left as
/// they are).
void give_kept_vectors(Eigen::VectorXd& a, Eigen::VectorXd& b) noexcept;

/// n T (trivially destructible, not initialised): a pooled block when large, else Eigen's.
template <class T>
class PooledArray {
 public:
  explicit PooledArray(std::ptrdiff_t n)
      : bytes_(sizeof(T) * std::size_t(n)),
        data_(static_cast<T*>(pooled() ? take_block(bytes_)
                                       : Eigen::internal::aligned_malloc(bytes_))) {}
  PooledArray(PooledArray&& o) noexcept
      : bytes_(std::exchange(o.bytes_, 0)), data_(std::exchange(o.data_, nullptr)) {}
  PooledArray(const PooledArray&) = delete;
  PooledArray& operator=(const PooledArray&) = delete;
  ~PooledArray() {
    if (!data_) return;
    if (pooled())
      give_block(data_, bytes_);
    else
      Eigen::internal::aligned_free(data_);
  }
  T* data() { return data_; }

 private:
  bool pooled() const { return bytes_ >= kPooledBytes; }
  std::size_t bytes_;
  T* data_;
};

}  // namespace erkn::detail
