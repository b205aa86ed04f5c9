// SPDX-License-Identifier: Apache-2.0
// The fixed_axes parser (lookup/src/flat_json.hpp).
#include "flat_json.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace railtab::lookup::detail {
namespace {

TEST(FlatJson, ParsesObjectsOfNumbers) {
  const auto v = parse_flat_json_numbers(R"( {"roll":0.0, "load" : 78500.0,"phi":-1.5e-3} )");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].first, "roll");
  EXPECT_EQ(v[1].second, 78500.0);
  EXPECT_EQ(v[2].second, -1.5e-3);
  EXPECT_TRUE(parse_flat_json_numbers("{}").empty());
}

TEST(FlatJson, RejectsOtherShapes) {
  EXPECT_THROW(parse_flat_json_numbers(R"({"roll":"zero"})"), std::runtime_error);
  EXPECT_THROW(parse_flat_json_numbers(R"({"roll":{"a":1}})"), std::runtime_error);
  EXPECT_THROW(parse_flat_json_numbers(R"({"roll":1,})"), std::runtime_error);
  EXPECT_THROW(parse_flat_json_numbers(R"({"roll":1} x)"), std::runtime_error);
  EXPECT_THROW(parse_flat_json_numbers(""), std::runtime_error);
}

TEST(FlatJson, GeneralParserKeepsStrings) {
  const auto v = parse_flat_json(R"({"eta":0.0,"roll":"equilibrium"})");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_FALSE(v[0].is_text);
  EXPECT_EQ(v[0].number, 0.0);
  EXPECT_TRUE(v[1].is_text);
  EXPECT_EQ(v[1].key, "roll");
  EXPECT_EQ(v[1].text, "equilibrium");
  EXPECT_THROW(parse_flat_json(R"({"roll":["equilibrium"]})"), std::runtime_error);
}

}  // namespace
}  // namespace railtab::lookup::detail
