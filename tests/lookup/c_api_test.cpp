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
  testing::write_fixture(file.path, testing::default_scene_spec());
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

}  // namespace
}  // namespace railtab::lookup
