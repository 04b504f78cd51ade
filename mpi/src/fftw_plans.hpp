// A forward and an inverse FFTW plan over one pair of buffers, freed together: the FFTW resources
// of a distributed transform (slab_transform.hpp, circulant_transform.hpp).
#pragma once

#include <fftw3-mpi.h>

namespace erkn::mpi::detail {

template <class T>  // double (real-to-real plans) or fftw_complex (DFTs)
struct FftwPlans {
  FftwPlans() = default;
  FftwPlans(const FftwPlans&) = delete;
  FftwPlans& operator=(const FftwPlans&) = delete;
  ~FftwPlans() {
    if (forward) fftw_destroy_plan(forward);
    if (inverse) fftw_destroy_plan(inverse);
    fftw_free(in);
    fftw_free(out);
  }
  T *in = nullptr, *out = nullptr;  // (FFTW-MPI's local size, including transpose room)
  fftw_plan forward = nullptr, inverse = nullptr;
};

}  // namespace erkn::mpi::detail
