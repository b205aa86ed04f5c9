// SPDX-License-Identifier: Apache-2.0
// Writes the raw bytes of every lookup result at many states of a table (random in range, 5 %
// out of range, within 0.1 mm of a contact jump, on grid nodes, a few ulps from a jump; both
// wheels; Table::query and query_slot of every slot; linear, cubic and monotone cubic), so two
// builds of the lookup can be compared byte for byte (speed-ups that must not change a result):
//   g++ -O2 -std=c++20 -Ilookup/include -I/usr/include/hdf5/serial scripts/lookup_result_dump.cpp
//     build/release/lookup/librailtab_lookup.a -L/usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -o dump
//   ./dump default.h5 after.bin [states]; cmp before.bin after.bin
// (default.h5 from `railtab generate tables/default.toml -o default.h5`).
#include <hdf5.h>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <random>
#include <string>
#include <vector>
#include "railtab/lookup.hpp"
namespace lk = railtab::lookup;

std::vector<double> read_jumps(const char* path) {
  std::vector<double> out;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  for (const char* name : {"/jumps/left_y", "/jumps/right_y"}) {
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    hid_t sp = H5Dget_space(d);
    hssize_t n = H5Sget_simple_extent_npoints(sp);
    std::vector<double> v(n);
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    for (double y : v) if (std::isfinite(y)) out.push_back(y);
    H5Sclose(sp); H5Dclose(d);
  }
  H5Fclose(f);
  return out;
}

void set_var(lk::State& s, const std::string& name, double x) {
  if (name == "y") s.y = x; else if (name == "roll") s.roll = x; else if (name == "load") s.load = x;
  else if (name == "xi") s.xi = x; else if (name == "eta") s.eta = x; else if (name == "phi") s.phi = x;
}

int main(int argc, char** argv) {
  const char* path = argv[1];
  FILE* out = std::fopen(argv[2], "wb");
  const int n = argc > 3 ? std::atoi(argv[3]) : 20000;
  const std::vector<double> jumps = read_jumps(path);
  for (lk::Method m : {lk::Method::kLinear, lk::Method::kCubic, lk::Method::kMonotoneCubic}) {
    const lk::Table t = lk::Table::load(path, {m});
    std::mt19937 rng(42);
    const int count = m == lk::Method::kMonotoneCubic ? n / 10 : n;
    for (int k = 0; k < count; ++k) {
      lk::State s = t.default_state();
      const int kind = k % 5;
      for (const lk::AxisInfo& a : t.axes()) {
        const double lo = a.nodes.front(), hi = a.nodes.back(), w = hi - lo;
        double x;
        if (kind == 1) x = std::uniform_real_distribution<double>(lo - 0.05 * w, hi + 0.05 * w)(rng);
        else if (kind == 3 && a.nodes.size() > 2) x = a.nodes[std::uniform_int_distribution<int>(0, a.nodes.size() - 1)(rng)];
        else x = std::uniform_real_distribution<double>(lo, hi)(rng);
        set_var(s, a.name, x);
      }
      if (kind == 2 || kind == 4) {
        const double j = jumps[std::uniform_int_distribution<int>(0, jumps.size() - 1)(rng)];
        s.y = j + std::uniform_real_distribution<double>(-1e-4, 1e-4)(rng);
        if (kind == 4) s.y = j + ((k / 5) % 2 ? 1 : -1) * std::ldexp(1.0, -30 - (k / 10) % 20);
      }
      const lk::Wheel wheel = static_cast<lk::Wheel>(k % 2);
      lk::Result r;
      t.query(wheel, s, r);
      std::fwrite(&r, sizeof r.n_slots, 1, out);
      std::fwrite(&r.status, sizeof r.status, 1, out);
      for (int sl = 0; sl < r.n_slots; ++sl) std::fwrite(&r.contact[sl], sizeof(lk::Contact), 1, out);
      for (int sl = 0; sl < t.n_slots(); ++sl) {
        lk::Contact c;
        t.query_slot(wheel, s, sl, c);
        std::fwrite(&c, sizeof c, 1, out);
      }
    }
  }
  std::fclose(out);
  std::printf("jumps %zu\n", jumps.size());
}
