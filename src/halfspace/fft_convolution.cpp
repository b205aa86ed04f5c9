// SPDX-License-Identifier: Apache-2.0
#include "halfspace/fft_convolution.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <utility>

namespace railtab::halfspace {
namespace {

struct Plans {
  fftw_plan r2c = nullptr;
  fftw_plan c2r = nullptr;
};

// One pair of plans per padded size for the life of the program (a few sizes in practice).
Plans plans_for(int px, int py) {
  static std::mutex mutex;
  static std::map<std::pair<int, int>, Plans> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find({px, py});
  if (it != cache.end()) return it->second;
  double* in = fftw_alloc_real(static_cast<size_t>(px) * py);
  fftw_complex* out = fftw_alloc_complex(static_cast<size_t>(py) * (px / 2 + 1));
  if (in == nullptr || out == nullptr) throw std::bad_alloc();
  Plans p;
  // Row-major py x px: the last (contiguous) dimension is x.
  p.r2c = fftw_plan_dft_r2c_2d(py, px, in, out, FFTW_ESTIMATE);
  p.c2r = fftw_plan_dft_c2r_2d(py, px, out, in, FFTW_ESTIMATE);
  fftw_free(in);
  fftw_free(out);
  if (p.r2c == nullptr || p.c2r == nullptr) throw std::bad_alloc();
  cache.emplace(std::make_pair(px, py), p);
  return p;
}

// Smallest n' >= n whose prime factors are 2, 3, 5 and 7 (FFTW is fastest on those; a padded
// length with a large prime factor costs several times more).
int fft_friendly(int n) {
  for (int m = n;; ++m) {
    int r = m;
    for (int f : {2, 3, 5, 7})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

}  // namespace

FftConvolver::~FftConvolver() { release(); }

void FftConvolver::release() {
  fftw_free(real_);
  fftw_free(spec_);
  real_ = nullptr;
  spec_ = nullptr;
}

void FftConvolver::resize(int nx, int ny) {
  if (nx == nx_ && ny == ny_ && real_ != nullptr) return;
  release();
  nx_ = nx;
  ny_ = ny;
  px_ = fft_friendly(2 * nx);
  py_ = fft_friendly(2 * ny);
  real_ = fftw_alloc_real(static_cast<size_t>(px_) * py_);
  spec_ = fftw_alloc_complex(static_cast<size_t>(py_) * (px_ / 2 + 1));
  if (real_ == nullptr || spec_ == nullptr) throw std::bad_alloc();
  const Plans p = plans_for(px_, py_);
  plan_r2c_ = p.r2c;
  plan_c2r_ = p.c2r;
}

void FftConvolver::kernel_spectrum(const std::function<double(int, int)>& kernel, Spectrum& out) {
  // Offset of padded index a along a padded length P >= 2n: a for a < n, a - P for a > P - n;
  // the indices between are never reached by a linear convolution of n-long fields (kept 0).
  for (int b = 0; b < py_; ++b) {
    const bool jin = b < ny_ || b > py_ - ny_;
    const int dj = b < ny_ ? b : b - py_;
    for (int a = 0; a < px_; ++a) {
      const bool iin = a < nx_ || a > px_ - nx_;
      const int di = a < nx_ ? a : a - px_;
      real_[static_cast<size_t>(b) * px_ + a] = (iin && jin) ? kernel(di, dj) : 0.0;
    }
  }
  fftw_execute_dft_r2c(static_cast<fftw_plan>(plan_r2c_), real_,
                       static_cast<fftw_complex*>(spec_));
  const size_t n = static_cast<size_t>(py_) * (px_ / 2 + 1);
  out.resize(n);
  std::memcpy(static_cast<void*>(out.data()), spec_, n * sizeof(fftw_complex));
}

void FftConvolver::forward(const double* field, Spectrum& out) {
  std::fill(real_, real_ + static_cast<size_t>(px_) * py_, 0.0);
  for (int j = 0; j < ny_; ++j)
    std::memcpy(real_ + static_cast<size_t>(j) * px_, field + static_cast<size_t>(j) * nx_,
                nx_ * sizeof(double));
  fftw_execute_dft_r2c(static_cast<fftw_plan>(plan_r2c_), real_,
                       static_cast<fftw_complex*>(spec_));
  const size_t n = static_cast<size_t>(py_) * (px_ / 2 + 1);
  out.resize(n);
  std::memcpy(static_cast<void*>(out.data()), spec_, n * sizeof(fftw_complex));
}

void FftConvolver::convolve(const Spectrum* const* kernels, const Spectrum* const* fields,
                            int terms, double* out) {
  const size_t n = static_cast<size_t>(py_) * (px_ / 2 + 1);
  auto* acc = static_cast<std::complex<double>*>(spec_);  // fftw_complex is layout-compatible
  for (size_t k = 0; k < n; ++k) {
    std::complex<double> s = (*kernels[0])[k] * (*fields[0])[k];
    for (int t = 1; t < terms; ++t) s += (*kernels[t])[k] * (*fields[t])[k];
    acc[k] = s;
  }
  fftw_execute_dft_c2r(static_cast<fftw_plan>(plan_c2r_),
                       static_cast<fftw_complex*>(spec_), real_);
  const double scale = 1.0 / (static_cast<double>(px_) * py_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      out[static_cast<size_t>(j) * nx_ + i] = real_[static_cast<size_t>(j) * px_ + i] * scale;
}

}  // namespace railtab::halfspace
