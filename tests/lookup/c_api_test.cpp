// SPDX-License-Identifier: Apache-2.0
// C API: return codes, thread-local last error, results identical to the C++ API.
#include "railtab_lookup.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <thread>

#include "lookup/lookup_test_util.hpp"
#include "lookup/table_fixture.hpp"
#include "railtab/lookup.hpp"

namespace railtab::lookup {
namespace {

TEST(CApi, OpenFailureReturnsCodeAndMessage) {
  railtab_lookup_table* t = reinterpret_cast<railtab_lookup_table*>(0x1);
  const std::string path = testing::temp_table("missing");
  EXPECT_EQ(railtab_lookup_open(path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_ERROR_LOAD);
  EXPECT_EQ(t, nullptr);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find(path), std::string::npos);
  // The message is per thread: another thread sees its own (empty) one.
  std::string other = "unset";
  std::thread([&] { other = railtab_lookup_last_error(); }).join();
  EXPECT_EQ(other, "");
}

TEST(CApi, BadArguments) {
  railtab_lookup_table* t = nullptr;
  EXPECT_EQ(railtab_lookup_open(nullptr, 0, &t), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_EQ(railtab_lookup_open("x.h5", 0, nullptr), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_EQ(railtab_lookup_open("x.h5", 9, &t), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("method"), std::string::npos);
  railtab_lookup_state s{};
  railtab_lookup_result r;
  EXPECT_EQ(railtab_lookup_query(nullptr, 0, &s, &r), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  railtab_lookup_close(nullptr);  // allowed
}

TEST(CApi, QueriesMatchTheCppApi) {
  testing::TempFile file("capi");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_CUBIC, &t), RAILTAB_LOOKUP_OK)
      << railtab_lookup_last_error();
  const Table cpp = Table::load(file.path, {Method::kCubic});

  railtab_lookup_state s;
  ASSERT_EQ(railtab_lookup_default_state(t, &s), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(s.load, 78500.0);
  EXPECT_EQ(s.roll, 0.0);
  s.y = 0.0021, s.xi = 0.0013, s.eta = -0.002, s.phi = 0.3;
  railtab_lookup_result r;
  ASSERT_EQ(railtab_lookup_query(t, RAILTAB_LOOKUP_RIGHT, &s, &r), RAILTAB_LOOKUP_OK);
  const Result expect = cpp.query(Wheel::kRight, State{s.y, s.roll, s.load, s.xi, s.eta, s.phi});
  EXPECT_EQ(r.n_slots, 2);
  EXPECT_EQ(r.status, 0u);
  EXPECT_EQ(std::memcmp(&r.contact[0], &expect.contact[0], 2 * sizeof(railtab_lookup_contact)), 0);
  EXPECT_EQ(r.contact[0].value[RAILTAB_LOOKUP_FX], expect.contact[0].value[kFx]);
  EXPECT_EQ(railtab_lookup_query(t, 2, &s, &r), RAILTAB_LOOKUP_ERROR_ARGUMENT);

  // Batch: both wheels, one out of range.
  const int wheels[3] = {RAILTAB_LOOKUP_LEFT, RAILTAB_LOOKUP_RIGHT, RAILTAB_LOOKUP_LEFT};
  railtab_lookup_state states[3] = {s, s, s};
  states[2].y = 1.0;
  railtab_lookup_result results[3];
  ASSERT_EQ(railtab_lookup_query_batch(t, 3, wheels, states, results), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(std::memcmp(&results[1].contact[0], &r.contact[0], 2 * sizeof(railtab_lookup_contact)), 0);
  EXPECT_EQ(results[2].status, RAILTAB_LOOKUP_OUT_OF_RANGE);
  EXPECT_TRUE(results[2].contact[0].status & RAILTAB_LOOKUP_OUT_OF_RANGE);
  EXPECT_EQ(railtab_lookup_query_batch(t, 0, nullptr, nullptr, nullptr), RAILTAB_LOOKUP_OK);
  railtab_lookup_close(t);
}

// Roll following the equilibrium is not an input: a C caller that sets one gets the answer at the
// equilibrium flagged RAILTAB_LOOKUP_OUT_OF_RANGE (query bits and every slot), never silently.
TEST(CApi, TrackForcesMatchTheCppApi) {
  testing::TempFile file("capi_track");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_OK)
      << railtab_lookup_last_error();
  const Table cpp = Table::load(file.path);
  railtab_lookup_state s;
  ASSERT_EQ(railtab_lookup_default_state(t, &s), RAILTAB_LOOKUP_OK);
  int loaded = 0;
  for (int wheel : {RAILTAB_LOOKUP_LEFT, RAILTAB_LOOKUP_RIGHT}) {
    for (double y : {-0.0031, 0.0007, 0.0023}) {
      s.y = y, s.xi = 0.0011, s.eta = -0.0015, s.phi = 0.2;
      railtab_lookup_result r;
      ASSERT_EQ(railtab_lookup_query(t, wheel, &s, &r), RAILTAB_LOOKUP_OK);
      railtab_lookup_track_forces c;
      ASSERT_EQ(railtab_lookup_compute_track_forces(wheel, &r, &c), RAILTAB_LOOKUP_OK);
      const TrackForces expect =
          track_forces(static_cast<Wheel>(wheel), cpp.query(static_cast<Wheel>(wheel), State{s.y, s.roll, s.load, s.xi, s.eta, s.phi}));
      EXPECT_EQ(std::memcmp(&c, &expect, sizeof c), 0) << wheel << " " << y;
      loaded += expect.q_force != 0.0;
    }
  }
  EXPECT_GT(loaded, 0);  // the comparison saw loaded slots, not only zeros
  railtab_lookup_result r{};
  railtab_lookup_track_forces c;
  EXPECT_EQ(railtab_lookup_compute_track_forces(RAILTAB_LOOKUP_LEFT, nullptr, &c), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_EQ(railtab_lookup_compute_track_forces(2, &r, &c), RAILTAB_LOOKUP_ERROR_ARGUMENT);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("wheel"), std::string::npos);
  railtab_lookup_close(t);
}

TEST(CApi, RollOnAnEquilibriumRollTableIsFlagged) {
  testing::TempFile file("capi_roll");
  testing::FixtureSpec spec = testing::scene_sized_spec();
  spec.fixed = {{2, 78500.0}};
  spec.fixed_text = "\"roll\":\"equilibrium\"";
  testing::write_fixture(file.path, spec);
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_OK)
      << railtab_lookup_last_error();
  railtab_lookup_state s;
  ASSERT_EQ(railtab_lookup_default_state(t, &s), RAILTAB_LOOKUP_OK);
  s.y = 0.003;
  railtab_lookup_result at_equilibrium, rolled;
  ASSERT_EQ(railtab_lookup_query(t, RAILTAB_LOOKUP_LEFT, &s, &at_equilibrium), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(at_equilibrium.status, 0u);
  s.roll = 0.004;
  ASSERT_EQ(railtab_lookup_query(t, RAILTAB_LOOKUP_LEFT, &s, &rolled), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(rolled.status, RAILTAB_LOOKUP_OUT_OF_RANGE);
  EXPECT_TRUE(rolled.contact[0].status & RAILTAB_LOOKUP_OUT_OF_RANGE);
  EXPECT_EQ(rolled.contact[0].value[RAILTAB_LOOKUP_FX], at_equilibrium.contact[0].value[RAILTAB_LOOKUP_FX]);
  railtab_lookup_contact c;
  ASSERT_EQ(railtab_lookup_query_slot(t, RAILTAB_LOOKUP_LEFT, &s, 1, &c), RAILTAB_LOOKUP_OK);
  EXPECT_TRUE(c.status & RAILTAB_LOOKUP_OUT_OF_RANGE);
  railtab_lookup_close(t);
}

}  // namespace
}  // namespace railtab::lookup

namespace railtab::lookup {
namespace {

// Every status bit of src/core/status.hpp in the C API (values checked at
// compile time in c_api.cpp and against the core in status_bits_test.cpp), and their names.
TEST(CApiComplete, StatusBitNamesAndText) {
  const uint32_t bits[RAILTAB_LOOKUP_NUM_STATUS_BITS] = {
      RAILTAB_LOOKUP_CONVERGED,         RAILTAB_LOOKUP_NOT_CONVERGED,
      RAILTAB_LOOKUP_TWO_POINT,         RAILTAB_LOOKUP_LIFT_OFF,
      RAILTAB_LOOKUP_CURVATURE_CLIPPED, RAILTAB_LOOKUP_CURVATURE_SHIFTED,
      RAILTAB_LOOKUP_FALLBACK_MODEL,    RAILTAB_LOOKUP_FLANGE_CONTACT,
      RAILTAB_LOOKUP_NON_HERTZIAN,      RAILTAB_LOOKUP_FULL_SLIP,
      RAILTAB_LOOKUP_OUT_OF_RANGE,      RAILTAB_LOOKUP_INVALID_INPUT,
      RAILTAB_LOOKUP_PROFILE_EDGE,      RAILTAB_LOOKUP_FAILED,
      RAILTAB_LOOKUP_AREA_TOO_SMALL,    RAILTAB_LOOKUP_NOT_PLANAR,
      RAILTAB_LOOKUP_NEAR_EQUAL_MINIMA, RAILTAB_LOOKUP_CURVATURE_STEP,
      RAILTAB_LOOKUP_LOW_CONFIDENCE};
  for (int b = 0; b < RAILTAB_LOOKUP_NUM_STATUS_BITS; ++b) {
    EXPECT_EQ(bits[b], 1u << b);
    EXPECT_STRNE(railtab_lookup_status_bit_name(bits[b]), "unknown");
  }
  EXPECT_STREQ(railtab_lookup_status_bit_name(RAILTAB_LOOKUP_FAILED), "failed");
  EXPECT_STREQ(railtab_lookup_status_bit_name(3u), "unknown");
  char buf[64];
  const uint32_t s = RAILTAB_LOOKUP_CONVERGED | RAILTAB_LOOKUP_TWO_POINT | (1u << 20);
  EXPECT_EQ(railtab_lookup_status_text(s, buf, sizeof buf), std::strlen("converged,two_point,bit20"));
  EXPECT_STREQ(buf, "converged,two_point,bit20");
  EXPECT_EQ(std::string(buf), status::describe(s));
  EXPECT_EQ(railtab_lookup_status_text(0, buf, sizeof buf), 4u);
  EXPECT_STREQ(buf, "none");
  // Too short: truncated, terminated, and the full length returned (as snprintf).
  char small[6];
  EXPECT_EQ(railtab_lookup_status_text(s, small, sizeof small), 25u);
  EXPECT_STREQ(small, "conve");
  EXPECT_EQ(railtab_lookup_status_text(s, nullptr, 0), 25u);
}

TEST(CApiComplete, IntrospectionAndVersions) {
  testing::TempFile file("info");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_OK)
      << railtab_lookup_last_error();
  railtab_lookup_table_info info;
  ASSERT_EQ(railtab_lookup_info(t, &info), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(std::string(info.path), file.path);
  EXPECT_STREQ(info.format_version, "1.0");
  EXPECT_STREQ(info.scene_name, "fixture");
  EXPECT_EQ(info.n_axes, 4);   // y, xi, eta, phi
  EXPECT_EQ(info.n_fixed, 2);  // roll, load
  EXPECT_EQ(info.n_slots, 2);
  for (int p = 0; p < RAILTAB_LOOKUP_NUM_PARTS; ++p) EXPECT_EQ(info.has_part[p], 1);
  EXPECT_EQ(info.checksums_verified, 1);
  EXPECT_GT(info.memory_bytes, 0u);

  const char* name = nullptr;
  const char* units = nullptr;
  size_t n = 0;
  const double* nodes = nullptr;
  ASSERT_EQ(railtab_lookup_axis(t, 0, &name, &units, &n, &nodes), RAILTAB_LOOKUP_OK);
  EXPECT_STREQ(name, "y");
  EXPECT_STREQ(units, "m");
  ASSERT_EQ(n, 41u);
  EXPECT_EQ(nodes[0], -0.01);
  EXPECT_EQ(nodes[40], 0.01);
  ASSERT_EQ(railtab_lookup_axis(t, 3, &name, &units, nullptr, nullptr), RAILTAB_LOOKUP_OK);
  EXPECT_STREQ(name, "phi");
  EXPECT_STREQ(units, "rad/m");
  EXPECT_EQ(railtab_lookup_axis(t, 4, &name, nullptr, nullptr, nullptr), RAILTAB_LOOKUP_ERROR_RANGE);
  EXPECT_EQ(railtab_lookup_axis(t, -1, &name, nullptr, nullptr, nullptr), RAILTAB_LOOKUP_ERROR_RANGE);
  double value = 0;
  ASSERT_EQ(railtab_lookup_fixed_axis(t, 1, &name, &value), RAILTAB_LOOKUP_OK);
  EXPECT_STREQ(name, "load");
  EXPECT_EQ(value, 78500.0);
  EXPECT_EQ(railtab_lookup_fixed_axis(t, 2, &name, &value), RAILTAB_LOOKUP_ERROR_RANGE);

  EXPECT_STREQ(railtab_lookup_output_name(RAILTAB_LOOKUP_FX), "fx");
  EXPECT_STREQ(railtab_lookup_output_units(RAILTAB_LOOKUP_MZ), "N m");
  EXPECT_STREQ(railtab_lookup_output_units(RAILTAB_LOOKUP_WEAR_RATE), "m2/m");
  EXPECT_EQ(railtab_lookup_output_part(RAILTAB_LOOKUP_SEMI_AXIS_B), RAILTAB_LOOKUP_NORMAL);
  EXPECT_EQ(railtab_lookup_output_part(RAILTAB_LOOKUP_NUM_OUTPUTS), -1);
  EXPECT_STREQ(railtab_lookup_part_name(RAILTAB_LOOKUP_CREEP), "creep");
  EXPECT_STREQ(railtab_lookup_slot_name(1), "flange");
  EXPECT_EQ(std::string(railtab_lookup_version()), library_version());
  EXPECT_STREQ(railtab_lookup_format_version(), "2.4");
  railtab_lookup_close(t);
}

// A short results buffer is an error code (nothing written), never a silent truncation; the C++
// batch returns false.
TEST(CApiComplete, ShortBatchBufferIsAnError) {
  testing::TempFile file("batch");
  testing::write_fixture(file.path, testing::scene_sized_spec());
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_OK);
  railtab_lookup_state s;
  railtab_lookup_default_state(t, &s);
  const int wheels[3] = {0, 1, 0};
  const railtab_lookup_state states[3] = {s, s, s};
  railtab_lookup_result results[3];
  results[0].n_slots = -7;
  EXPECT_EQ(railtab_lookup_query_batch_checked(t, 3, wheels, states, results, 2),
            RAILTAB_LOOKUP_ERROR_BUFFER);
  EXPECT_EQ(results[0].n_slots, -7);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("fewer results"), std::string::npos);
  EXPECT_EQ(railtab_lookup_query_batch_checked(t, 3, wheels, states, results, 3), RAILTAB_LOOKUP_OK);
  EXPECT_EQ(results[0].n_slots, 2);
  railtab_lookup_close(t);

  const Table cpp = Table::load(file.path);
  std::vector<Query> q(3);
  std::vector<Result> r(2);
  r[0].n_slots = -7;
  EXPECT_FALSE(cpp.query(q, r));
  EXPECT_EQ(r[0].n_slots, -7);
  r.resize(3);
  EXPECT_TRUE(cpp.query(q, r));
  EXPECT_EQ(r[0].n_slots, 2);
}

TEST(CApiComplete, RequireChecksumsFlag) {
  testing::TempFile file("legacy");
  testing::FixtureSpec spec = testing::scene_sized_spec();
  spec.checksums = false;
  spec.checksummed_metadata = true;  // a format-1.0 table (superblock 0) is refused either way
  testing::write_fixture(file.path, spec);
  railtab_lookup_table* t = nullptr;
  ASSERT_EQ(railtab_lookup_open(file.path.c_str(), RAILTAB_LOOKUP_LINEAR, &t), RAILTAB_LOOKUP_OK);
  railtab_lookup_table_info info;
  railtab_lookup_info(t, &info);
  EXPECT_EQ(info.checksums_verified, 0);
  railtab_lookup_close(t);
  EXPECT_EQ(railtab_lookup_open_options(file.path.c_str(), RAILTAB_LOOKUP_LINEAR,
                                        RAILTAB_LOOKUP_REQUIRE_CHECKSUMS, &t),
            RAILTAB_LOOKUP_ERROR_LOAD);
  EXPECT_NE(std::string(railtab_lookup_last_error()).find("no checksums"), std::string::npos);
  EXPECT_EQ(railtab_lookup_open_options(file.path.c_str(), 0, 8u, &t), RAILTAB_LOOKUP_ERROR_ARGUMENT);
}

}  // namespace
}  // namespace railtab::lookup
