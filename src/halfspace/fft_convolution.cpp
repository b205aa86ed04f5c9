// SPDX-License-Identifier: Apache-2.0
// Convolution of grid fields with influence kernels by FFT (fft_convolution.hpp).
#include "halfspace/fft_convolution.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <tuple>
#include <utility>

namespace railtab::halfspace {
namespace {

struct Plans {
  fftw_plan r2c = nullptr;      // full 2D transform (kernels: every row is non-zero)
  fftw_plan row_r2c = nullptr;  // rows 0..ny-1 along x (the rest of a padded field is zero)
  fftw_plan col_fwd = nullptr;  // every column along y, in place
  fftw_plan col_bwd = nullptr;  // every column along y, in place, inverse
  fftw_plan row_c2r = nullptr;  // rows 0..ny-1 back along x (only those are read)
};

void destroy(const Plans& p) {
  for (fftw_plan q : {p.r2c, p.row_r2c, p.col_fwd, p.col_bwd, p.row_c2r})
    if (q != nullptr) fftw_destroy_plan(q);
}

// The plans made so far, destroyed at exit (a leak checker then sees every FFTW allocation freed).
struct PlanCache {
  std::mutex mutex;
  std::map<std::tuple<int, int, int>, Plans> plans;
  ~PlanCache() {
    for (const auto& entry : plans) destroy(entry.second);
  }
};

// One set of plans per padded size and field height for the life of the program (a few in
// practice). The 2D transform of a zero-padded field is done as row transforms of the ny
// non-zero rows followed by column transforms, and the inverse as column transforms followed by
// row transforms of the ny rows that are kept: about a quarter fewer operations than the full
// 2D transforms and no internal copies; the result is the same transform.
Plans plans_for(int px, int py, int ny) {
  static PlanCache cache;
  const std::lock_guard<std::mutex> lock(cache.mutex);
  auto it = cache.plans.find({px, py, ny});
  if (it != cache.plans.end()) return it->second;
  const int cx = px / 2 + 1;  // complex values per row
  double* in = fftw_alloc_real(static_cast<size_t>(px) * py);
  fftw_complex* out = fftw_alloc_complex(static_cast<size_t>(py) * cx);
  if (in == nullptr || out == nullptr) {
    fftw_free(in);
    fftw_free(out);
    throw std::bad_alloc();
  }
  Plans p;
  // Row-major py x px: the last (contiguous) dimension is x.
  p.r2c = fftw_plan_dft_r2c_2d(py, px, in, out, FFTW_ESTIMATE);
  p.row_r2c = fftw_plan_many_dft_r2c(1, &px, ny, in, nullptr, 1, px, out, nullptr, 1, cx,
                                     FFTW_ESTIMATE);
  p.col_fwd = fftw_plan_many_dft(1, &py, cx, out, nullptr, cx, 1, out, nullptr, cx, 1,
                                 FFTW_FORWARD, FFTW_ESTIMATE);
  p.col_bwd = fftw_plan_many_dft(1, &py, cx, out, nullptr, cx, 1, out, nullptr, cx, 1,
                                 FFTW_BACKWARD, FFTW_ESTIMATE);
  p.row_c2r = fftw_plan_many_dft_c2r(1, &px, ny, out, nullptr, 1, cx, in, nullptr, 1, px,
                                     FFTW_ESTIMATE);
  fftw_free(in);
  fftw_free(out);
  if (p.r2c == nullptr || p.row_r2c == nullptr || p.col_fwd == nullptr ||
      p.col_bwd == nullptr || p.row_c2r == nullptr) {
    destroy(p);
    throw std::bad_alloc();
  }
  cache.plans.emplace(std::make_tuple(px, py, ny), p);
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
  fftw_free(real_in_);
  fftw_free(real_out_);
  fftw_free(spec_);
  real_in_ = real_out_ = nullptr;
  spec_ = nullptr;
}

void FftConvolver::resize(int nx, int ny) {
  if (nx == nx_ && ny == ny_ && real_in_ != nullptr) return;
  release();
  nx_ = nx;
  ny_ = ny;
  px_ = fft_friendly(2 * nx);
  py_ = fft_friendly(2 * ny);
  const size_t nr = static_cast<size_t>(px_) * py_;
  real_in_ = fftw_alloc_real(nr);
  real_out_ = fftw_alloc_real(nr);
  spec_ = fftw_alloc_complex(static_cast<size_t>(py_) * (px_ / 2 + 1));
  if (real_in_ == nullptr || real_out_ == nullptr || spec_ == nullptr) throw std::bad_alloc();
  std::fill(real_in_, real_in_ + nr, 0.0);
  const Plans p = plans_for(px_, py_, ny_);
  plan_r2c_ = p.r2c;
  plan_row_r2c_ = p.row_r2c;
  plan_col_fwd_ = p.col_fwd;
  plan_col_bwd_ = p.col_bwd;
  plan_row_c2r_ = p.row_c2r;
}

void FftConvolver::kernel_spectrum(const std::function<double(int, int)>& kernel, Spectrum& out) {
  // Offset of padded index a along a padded length P >= 2n: a for a < n, a - P for a > P - n;
  // the indices between are never reached by a linear convolution of n-long fields (kept 0).
  // The kernel is laid out in the output buffer (real_in_ must stay zero outside the field).
  for (int b = 0; b < py_; ++b) {
    const bool jin = b < ny_ || b > py_ - ny_;
    const int dj = b < ny_ ? b : b - py_;
    for (int a = 0; a < px_; ++a) {
      const bool iin = a < nx_ || a > px_ - nx_;
      const int di = a < nx_ ? a : a - px_;
      real_out_[static_cast<size_t>(b) * px_ + a] = (iin && jin) ? kernel(di, dj) : 0.0;
    }
  }
  out.resize(static_cast<size_t>(py_) * (px_ / 2 + 1));
  fftw_execute_dft_r2c(static_cast<fftw_plan>(plan_r2c_), real_out_,
                       reinterpret_cast<fftw_complex*>(out.data()));
}

void FftConvolver::forward(const double* field, Spectrum& out) {
  // Only the field's rows are written: the padding of real_in_ is zero since resize().
  for (int j = 0; j < ny_; ++j)
    std::memcpy(real_in_ + static_cast<size_t>(j) * px_, field + static_cast<size_t>(j) * nx_,
                nx_ * sizeof(double));
  const size_t cx = px_ / 2 + 1;
  out.resize(static_cast<size_t>(py_) * cx);
  auto* spec = reinterpret_cast<fftw_complex*>(out.data());
  fftw_execute_dft_r2c(static_cast<fftw_plan>(plan_row_r2c_), real_in_, spec);
  std::fill(out.begin() + static_cast<std::ptrdiff_t>(ny_ * cx), out.end(),
            std::complex<double>(0.0, 0.0));  // the transforms of the zero rows
  fftw_execute_dft(static_cast<fftw_plan>(plan_col_fwd_), spec, spec);
}

void FftConvolver::convolve(const Spectrum* const* kernels, const Spectrum* const* fields,
                            int terms, double* out) {
  const size_t n = static_cast<size_t>(py_) * (px_ / 2 + 1);
  auto* acc = static_cast<std::complex<double>*>(spec_);  // fftw_complex is layout-compatible
  const std::complex<double>* k0 = kernels[0]->data();
  const std::complex<double>* f0 = fields[0]->data();
  // Products written out: std::complex's operator* checks for NaN/inf results and is not
  // vectorised; the values are the same for finite input.
  auto mul = [](const std::complex<double>& a, const std::complex<double>& b) {
    return std::complex<double>(a.real() * b.real() - a.imag() * b.imag(),
                                a.real() * b.imag() + a.imag() * b.real());
  };
  if (terms == 1) {
    for (size_t k = 0; k < n; ++k) acc[k] = mul(k0[k], f0[k]);
  } else if (terms == 2) {
    const std::complex<double>* k1 = kernels[1]->data();
    const std::complex<double>* f1 = fields[1]->data();
    for (size_t k = 0; k < n; ++k) acc[k] = mul(k0[k], f0[k]) + mul(k1[k], f1[k]);
  } else {
    for (size_t k = 0; k < n; ++k) {
      std::complex<double> s = mul(k0[k], f0[k]);
      for (int t = 1; t < terms; ++t) s += mul((*kernels[t])[k], (*fields[t])[k]);
      acc[k] = s;
    }
  }
  auto* spec = static_cast<fftw_complex*>(spec_);
  fftw_execute_dft(static_cast<fftw_plan>(plan_col_bwd_), spec, spec);
  fftw_execute_dft_c2r(static_cast<fftw_plan>(plan_row_c2r_), spec, real_out_);
  const double scale = 1.0 / (static_cast<double>(px_) * py_);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      out[static_cast<size_t>(j) * nx_ + i] = real_out_[static_cast<size_t>(j) * px_ + i] * scale;
}

}  // namespace railtab::halfspace
