// SPDX-License-Identifier: Apache-2.0
// Storage precision of format 2.2 (docs/table-format.md, "Storage precision"): the STRIPES
// scene's table as `railtab generate` writes it (creep and wear outputs as float32 rounded to 20
// significant bits) against the same table written with float64 outputs (format 2.1), both
// through the lookup at random states, jump cells included, linear and cubic.
//
// The bound: every stored value v is within kStoredRounding |v| = 2^-20 |v| of the float64 one.
// Linear interpolation (and the one-sided interpolation of a jump cell) weights the corner values
// with weights >= 0 summing to 1, so an interpolated value moves by at most 2^-20 of the largest
// corner; a force is (F / (mu N) + law) mu N with |F / (mu N)| <= 2 and N rebuilt from the stored
// vertical share and fy / (mu N) (together <= 2 x 2^-20 relative), so it moves by at most
// 4 x 2^-20 of mu N. Stated bound, per output and slot: 4 x 2^-20 of the output's largest |value|
// over the states (fx, fy: mu times the largest normal force). The cubic weights are not all
// >= 0 (Hermite slopes: sum of |weights| <= 1.25 per axis, 3.05 over 5 axes): 12 x 2^-20 there.
// Measured: <= 0.68 (linear), <= 0.72 (cubic) x 2^-20; writing 16 significant bits instead of 20
// fails the linear test (checked).
// The geometry part and the normal part's outputs other than the normal force are float64 in
// both tables: there the answers must be the same bits.
// The lookup holds the 2.2 table's creep and wear records as floats (lookup/src/records.hpp):
// half their memory; its multilinear sums of them run in float (within a millionth of mu N of
// the double sums), every other answer has the same bits as with double records.
//
// Run: build/<dir>/tests/test_table_accuracy --gtest_filter='StoragePrecision*' (prints the
// numbers).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "accuracy_util.hpp"
#include "adaptive/jump_locator.hpp"
#include "table/storage_precision.hpp"

namespace railtab::accuracy::storage_precision_test {  // own namespace: unity builds compile several test files as one
namespace {

constexpr std::uint64_t kSeed = 20261126;
constexpr std::size_t kStates = 20000;  // per wheel

constexpr lk::Method kMethods[3] = {lk::Method::kLinear, lk::Method::kCubic, lk::Method::kMonotoneCubic};

struct Tables {
  Scene scene;
  std::optional<lk::Table> stored[2][2];  // [0 float32 (2.2), 1 float64 (2.1)][0 linear, 1 cubic]
  std::uintmax_t bytes[2] = {};           // file sizes [B]
  // The 2.2 table per method (kMethods): [0] as loaded (float records), [1] with double records
  // (RAILTAB_LOOKUP_NO_FLOAT_RECORDS=1).
  std::optional<lk::Table> records[2][3];
  // The 2.2 table's monotone cubic with float records and the SSE2 kernels (RAILTAB_LOOKUP_NO_AVX2=1).
  std::optional<lk::Table> monotone_sse2;
};

const Tables& tables() {
  static const Tables t = [] {
    Tables x;
    const StripesSweep& d = stripes_sweep();
    x.scene = d.scene;
    Table table = d.table;
    add_jumps(table, x.scene, d.jumps);
    if (!table_stores_float32(table)) throw std::runtime_error("the sweep's table is not format 2.2");
    Table doubles = table;
    doubles.set_attribute("format_version", "2.1");  // the layout before 2.2: float64 outputs
    for (int k = 0; k < 2; ++k) {
      const std::filesystem::path path = temp_table_path(k == 0 ? "float32" : "float64");
      write_for_lookup(k == 0 ? table : doubles, path);
      x.bytes[k] = std::filesystem::file_size(path);
      for (int m = 0; m < 2; ++m) {
        lk::LoadOptions options;
        options.method = m == 0 ? lk::Method::kLinear : lk::Method::kCubic;
        x.stored[k][m].emplace(lk::Table::load(path.string(), options));
      }
      for (int m = 0; m < 3 && k == 0; ++m) {
        lk::LoadOptions options;
        options.method = kMethods[m];
        x.records[0][m].emplace(lk::Table::load(path.string(), options));
        ::setenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS", "1", 1);
        x.records[1][m].emplace(lk::Table::load(path.string(), options));
        ::unsetenv("RAILTAB_LOOKUP_NO_FLOAT_RECORDS");
      }
      if (k == 0) {
        ::setenv("RAILTAB_LOOKUP_NO_AVX2", "1", 1);
        x.monotone_sse2.emplace(lk::Table::load(path.string(), lk::LoadOptions{lk::Method::kMonotoneCubic}));
        ::unsetenv("RAILTAB_LOOKUP_NO_AVX2");
      }
      std::filesystem::remove(path);
    }
    return x;
  }();
  return t;
}

bool float64_in_both(int o) {
  const lk::Part p = lk::output_part(static_cast<lk::Output>(o));
  return (p == lk::Part::kGeometry || p == lk::Part::kNormal) && o != lk::kNormalForce;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void compare(int method, double bound_in_roundings) {
  const Tables& t = tables();
  const lk::Table& single = *t.stored[0][method];
  const lk::Table& full = *t.stored[1][method];
  const Scene& s = t.scene;
  Random rng(kSeed + static_cast<std::uint64_t>(method));
  std::vector<lk::State> states(kStates);
  for (lk::State& st : states) {
    st = full.default_state();
    st.y = rng.uniform(s.grids.y.front(), s.grids.y.back());
    st.load = rng.uniform(s.grids.load.front(), s.grids.load.back());
    st.xi = rng.uniform(s.grids.xi.front(), s.grids.xi.back());
    st.eta = rng.uniform(s.grids.eta.front(), s.grids.eta.back());
    st.phi = rng.uniform(s.grids.phi.front(), s.grids.phi.back());
  }
  double diff[lk::kNumOutputs][kSlots] = {}, scale[lk::kNumOutputs][kSlots] = {};
  std::size_t differing_bits = 0;
  for (int w = 0; w < 2; ++w) {
    for (const lk::State& st : states) {
      const lk::Result a = single.query(static_cast<lk::Wheel>(w), st);
      const lk::Result b = full.query(static_cast<lk::Wheel>(w), st);
      for (std::size_t slot = 0; slot < kSlots; ++slot) {
        ASSERT_EQ(a.contact[slot].status, b.contact[slot].status) << "statuses are stored as before";
        for (int o = 0; o < lk::kNumOutputs; ++o) {
          const double va = a.contact[slot].value[o], vb = b.contact[slot].value[o];
          if (float64_in_both(o)) {
            if (!same_bits(va, vb)) ++differing_bits;
            continue;
          }
          diff[o][slot] = std::max(diff[o][slot], std::abs(va - vb));
          const bool force = o == lk::kFx || o == lk::kFy;
          const double size = force ? s.tangential.friction * b.contact[slot].value[lk::kNormalForce] : std::abs(vb);
          scale[o][slot] = std::max(scale[o][slot], size);
        }
      }
    }
  }
  EXPECT_EQ(differing_bits, 0u) << "geometry / normal outputs differ between the float32 and the float64 table";
  std::printf("storage precision, %s lookup, %zu random states x 2 wheels: max |float32 table - float64 table| "
              "/ (2^-20 x scale), scale = largest |value| (fx, fy: mu x largest N); limit %.0f\n",
              method == 0 ? "linear" : "cubic", kStates, bound_in_roundings);
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    if (float64_in_both(o)) continue;
    std::printf("  %-14s", lk::output_name(static_cast<lk::Output>(o)));
    for (std::size_t slot = 0; slot < kSlots; ++slot) {
      const double ratio = scale[o][slot] > 0.0 ? diff[o][slot] / (kStoredRounding * scale[o][slot]) : 0.0;
      std::printf("  slot %zu: %6.3f (max diff %.3g, scale %.3g)", slot, ratio, diff[o][slot], scale[o][slot]);
    }
    std::printf("\n");
    for (std::size_t slot = 0; slot < kSlots; ++slot)
      EXPECT_LE(diff[o][slot], bound_in_roundings * kStoredRounding * scale[o][slot])
          << lk::output_name(static_cast<lk::Output>(o)) << " slot " << slot;
  }
}

TEST(StoragePrecision, StripesTableIsSmallerThanTheFloat64One) {
  const Tables& t = tables();
  std::printf("STRIPES table file: %ju B with float32 outputs (2.2), %ju B with float64 (2.1)\n", t.bytes[0],
              t.bytes[1]);
  // A table in tables/ may take up to 64 MB on disk (docs/lookup-accuracy.md); float32 halves it.
  EXPECT_LE(t.bytes[0], 64000000u) << "table size limit: 64 MB";
  EXPECT_LT(t.bytes[0], t.bytes[1] / 2);
}

TEST(StoragePrecision, LinearLookupMovesByLessThanTheRoundingBound) { compare(0, 4.0); }

TEST(StoragePrecision, CubicLookupMovesByLessThanTheRoundingBound) { compare(1, 12.0); }

// The creep + wear block (5-D, 98 % of the records against the 1-D geometry and 2-D normal
// blocks) goes from 64-byte double to 32-byte float records: the data at most 0.55 of the double
// ones. The 2.1 table's float64 outputs are no floats: it stays double.
TEST(StoragePrecision, LookupHoldsTheFloat32OutputsAsFloats) {
  const Tables& t = tables();
  const std::size_t floats = t.records[0][0]->memory_bytes(), doubles = t.records[1][0]->memory_bytes();
  std::printf("STRIPES table in memory: %zu B with float records, %zu B with double records\n", floats, doubles);
  EXPECT_LE(static_cast<double>(floats), 0.55 * static_cast<double>(doubles));
  EXPECT_EQ(t.stored[1][0]->memory_bytes(), doubles) << "the float64 (2.1) table is held as doubles";
}

// Float records against double records (RAILTAB_LOOKUP_NO_FLOAT_RECORDS=1), every method, query
// and query_slot, both wheels, at random states in range and 5 % beyond (jump cells included) and
// on grid nodes. The cubic sums convert the floats to double (exact), as do the one-sided sums of
// jump cells: the same bytes. The multilinear corner sums of float records run in float
// (weighted_sum.hpp), and so do the monotone cubic's limited Hermite passes over the last two axes
// (interpolate_cubic.cpp): the same statuses, and every output within kFloatArithmetic of its
// scale (fx, fy: mu x the largest normal force; the others their largest |value|), the bound the
// lookup's float arithmetic is allowed (a millionth of mu N). The monotone cubic's float passes
// give the same bytes with the AVX2 and the SSE2 kernels.
constexpr double kFloatArithmetic = 1e-6;

TEST(StoragePrecision, FloatRecordsGiveTheBytesOfDoubleRecordsOrStayWithinTheFloatArithmeticBound) {
  const Tables& t = tables();
  const Scene& s = t.scene;
  Random rng(kSeed + 7);
  const std::vector<double>* grids[5] = {&s.grids.y, &s.grids.load, &s.grids.xi, &s.grids.eta, &s.grids.phi};
  std::size_t compared = 0, differing = 0, float_differing[3] = {};
  double diff[3][lk::kNumOutputs] = {}, scale[3][lk::kNumOutputs] = {};
  for (int m = 0; m < 3; ++m) {
    const lk::Table& single = *t.records[0][m];
    const lk::Table& full = *t.records[1][m];
    const std::size_t n = m == 2 ? 1000 : 5000;  // the monotone cubic is ~25x slower
    for (std::size_t k = 0; k < n; ++k) {
      double v[5];
      for (int a = 0; a < 5; ++a) {
        const double lo = grids[a]->front(), hi = grids[a]->back(), w = hi - lo;
        v[a] = k % 3 == 1 ? rng.uniform(lo - 0.05 * w, hi + 0.05 * w) : rng.uniform(lo, hi);
        if (k % 3 == 2) v[a] = (*grids[a])[static_cast<std::size_t>(rng.uniform(0.0, 1.0) * (grids[a]->size() - 1) + 0.5)];
      }
      lk::State st = full.default_state();
      st.y = v[0], st.load = v[1], st.xi = v[2], st.eta = v[3], st.phi = v[4];
      for (int w = 0; w < 2; ++w) {
        const lk::Wheel wheel = static_cast<lk::Wheel>(w);
        const lk::Result a = single.query(wheel, st), b = full.query(wheel, st);
        lk::Contact ca[kSlots], cb[kSlots];
        for (int slot = 0; slot < static_cast<int>(kSlots); ++slot) {
          ca[slot] = single.query_slot(wheel, st, slot);
          cb[slot] = full.query_slot(wheel, st, slot);
          ASSERT_EQ(std::memcmp(&ca[slot], &a.contact[slot], sizeof ca[slot]), 0) << "query_slot = query";
        }
        compared += 1 + kSlots;
        if (m == 2) {
          const lk::Result c = t.monotone_sse2->query(wheel, st);
          ASSERT_EQ(std::memcmp(&a, &c, sizeof a), 0) << "monotone cubic: SSE2 = AVX2";
        }
        if (m == 1) {
          differing += std::memcmp(&a, &b, sizeof a) != 0;
          for (std::size_t slot = 0; slot < kSlots; ++slot)
            differing += std::memcmp(&ca[slot], &cb[slot], sizeof ca[slot]) != 0;
          continue;
        }
        ASSERT_EQ(a.status, b.status);
        float_differing[m] += std::memcmp(&a, &b, sizeof a) != 0;
        for (std::size_t slot = 0; slot < kSlots; ++slot) {
          ASSERT_EQ(a.contact[slot].status, b.contact[slot].status);
          for (int o = 0; o < lk::kNumOutputs; ++o) {
            ASSERT_EQ(a.contact[slot].part_status[lk::output_part(static_cast<lk::Output>(o))],
                      b.contact[slot].part_status[lk::output_part(static_cast<lk::Output>(o))]);
            const double va = a.contact[slot].value[o], vb = b.contact[slot].value[o];
            diff[m][o] = std::max(diff[m][o], std::abs(va - vb));
            const bool force = o == lk::kFx || o == lk::kFy;
            scale[m][o] = std::max(scale[m][o], force ? s.tangential.friction * b.contact[slot].value[lk::kNormalForce]
                                                      : std::abs(vb));
          }
        }
      }
    }
  }
  EXPECT_EQ(differing, 0u) << "cubic: of " << compared << " results";
  for (int m : {0, 2}) {
    const char* name = m == 0 ? "linear" : "monotone cubic";
    std::printf("%s lookup, float arithmetic on float records: %zu results (query) differ from double records; "
                "max |difference| / scale (limit %.0e):\n", name, float_differing[m], kFloatArithmetic);
    for (int o = 0; o < lk::kNumOutputs; ++o) {
      if (scale[m][o] == 0.0) continue;
      std::printf("  %-14s %.3g (max diff %.3g, scale %.3g)\n", lk::output_name(static_cast<lk::Output>(o)),
                  diff[m][o] / scale[m][o], diff[m][o], scale[m][o]);
      EXPECT_LE(diff[m][o], kFloatArithmetic * scale[m][o]) << name << " " << lk::output_name(static_cast<lk::Output>(o));
    }
    EXPECT_GT(float_differing[m], 0u) << "the " << name << " lookup of float records should run in float";
  }
}

}  // namespace
}  // namespace railtab::accuracy::storage_precision_test
