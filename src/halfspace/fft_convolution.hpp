// SPDX-License-Identifier: Apache-2.0
// Discrete convolution of grid fields with influence kernels by FFT, DC-FFT style (Liu, Wang &
// Liu, Wear 243 (2000)): the field is zero-padded to at least twice its size in each direction
// (the next length with prime factors 2, 3, 5, 7 only, where FFTW is fast) and the
// kernel is laid out on the same doubled grid by offset (wrap-around order), so the cyclic
// convolution of the FFT equals the linear one of the boundary-element method exactly (to
// rounding): no aliasing, no approximation of the influence coefficients.
//
// FFT: FFTW 3 (Debian's libfftw3-dev). Plans are made with FFTW_ESTIMATE (no timing, so the same
// plan, hence the same bytes, on every run) once per padded size and field height and shared
// through a cache behind a mutex, because FFTW's planner is not thread-safe; executing a plan on
// new arrays (fftw_execute_dft*) is. Fields are transformed as rows (only the non-zero ones)
// then columns, and back as columns then the rows that are read (the .cpp). All arrays are
// 64-byte aligned so their alignment always matches the plan's.
#pragma once

#include <complex>
#include <cstddef>
#include <functional>
#include <new>
#include <vector>

namespace railtab::halfspace {

// Spectra live in 64-byte aligned storage so that FFTW can transform into and out of them
// directly (a plan may only be executed on arrays aligned as the ones it was made with; FFTW's
// own allocation is at most 64-byte aligned, so 64 always matches).
template <class T>
struct FftAlignedAllocator {
  using value_type = T;
  FftAlignedAllocator() = default;
  template <class U>
  FftAlignedAllocator(const FftAlignedAllocator<U>&) {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{64}));
  }
  void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t{64}); }
  template <class U>
  bool operator==(const FftAlignedAllocator<U>&) const { return true; }
};

using Spectrum = std::vector<std::complex<double>, FftAlignedAllocator<std::complex<double>>>;

class FftConvolver {
 public:
  FftConvolver() = default;
  ~FftConvolver();
  FftConvolver(const FftConvolver&) = delete;
  FftConvolver& operator=(const FftConvolver&) = delete;

  // Fields of nx * ny values (index j * nx + i). Reallocates only when the size changes.
  void resize(int nx, int ny);
  int nx() const { return nx_; }
  int ny() const { return ny_; }

  // Spectrum of a kernel given as a function of the element offset (di, dj) = field minus
  // source, |di| < nx, |dj| < ny.
  void kernel_spectrum(const std::function<double(int di, int dj)>& kernel, Spectrum& out);

  // Spectrum of a field (zero-padded).
  void forward(const double* field, Spectrum& out);

  // out = sum_k kernels[k] * fields[k] in Fourier space, back to the grid (nx * ny values).
  void convolve(const Spectrum* const* kernels, const Spectrum* const* fields, int terms,
                double* out);

 private:
  void release();
  int nx_ = 0, ny_ = 0;     // field size
  int px_ = 0, py_ = 0;     // padded size (>= 2 nx, >= 2 ny)
  double* real_in_ = nullptr;   // px * py, fftw_malloc'd; zero outside the nx * ny field
  double* real_out_ = nullptr;  // px * py, fftw_malloc'd; result of the inverse transform
  void* spec_ = nullptr;        // py * (px / 2 + 1) fftw_complex, fftw_malloc'd
  void* plan_r2c_ = nullptr;      // full 2D (kernels)
  void* plan_row_r2c_ = nullptr;  // zero-padded fields: rows, then columns (see the .cpp)
  void* plan_col_fwd_ = nullptr;
  void* plan_col_bwd_ = nullptr;
  void* plan_row_c2r_ = nullptr;
};

}  // namespace railtab::halfspace
