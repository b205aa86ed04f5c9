// SPDX-License-Identifier: Apache-2.0
// Numbers users type (core/number_input.hpp): one finite number in range, lists and fields of them,
// and refusals whose message names the input and quotes the text safely.
#include "core/number_input.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/check.hpp"
#include "error_message.hpp"

namespace railtab {
namespace {

constexpr NumberRule kY{-0.1, 0.1, false, "m"};
constexpr NumberRule kThreads{0, 1024, true, ""};

std::string problem(std::string_view text, const NumberRule& rule) {
  double v = 0.0;
  return number_problem(text, rule, v);
}

TEST(NumberInput, AcceptsOneFiniteNumberInRange) {
  EXPECT_DOUBLE_EQ(parse_number_input("0.003", "--y", kY), 0.003);
  EXPECT_DOUBLE_EQ(parse_number_input("-1e-3", "--y", kY), -1e-3);
  EXPECT_DOUBLE_EQ(parse_number_input("+0.1", "--y", kY), 0.1);
  EXPECT_DOUBLE_EQ(parse_number_input("1024", "--threads", kThreads), 1024.0);
  EXPECT_DOUBLE_EQ(parse_number_input("2e2", "--threads", kThreads), 200.0);
}

TEST(NumberInput, RefusesEmptyNanInfFractionAndOutOfRange) {
  EXPECT_NE(problem("", kY).find("empty value"), std::string::npos);
  EXPECT_NE(problem("nan", kY).find("NaN"), std::string::npos);
  EXPECT_NE(problem("NAN", kY).find("NaN"), std::string::npos);
  EXPECT_NE(problem("inf", kY).find("infinity"), std::string::npos);
  EXPECT_NE(problem("-infinity", kY).find("-infinity"), std::string::npos);
  EXPECT_NE(problem("0.2", kY).find("in [-0.1, 0.1] m, got 0.2 m"), std::string::npos);
  EXPECT_NE(problem("1e400", kY).find("not representable"), std::string::npos);
  EXPECT_NE(problem("1.5", kThreads).find("not a whole number"), std::string::npos);
  EXPECT_NE(problem("100000", kThreads).find("a whole number in [0, 1024]"), std::string::npos);
  EXPECT_NE(problem("-1", kThreads).find("got -1"), std::string::npos);
  for (const char* text : {"abc", "1,2", " 1", "1 ", "0x10", "1e", "+", "+-1", "--1", "1.2.3", "true"}) {
    EXPECT_NE(problem(text, kY).find("not a number"), std::string::npos) << text;
  }
}

TEST(NumberInput, MessageNamesTheInputAndQuotesTheTextSafely) {
  EXPECT_EQ(test::error_message([] { parse_number_input("abc", "--load", kY); }),
            "--load: must be a number in [-0.1, 0.1] m, got 'abc' (not a number)");
  // Control characters are escaped; long text is cut.
  // The text is built with += rather than operator+ on a temporary: GCC 12 takes the moved result
  // of that concatenation for a string in its 16-byte local buffer and warns of a copy past it
  // (GCC bug 109299, a false positive).
  std::string text = "1\n\x1b[2J";
  text += std::string(100, '9');
  const std::string m = test::error_message([&] { parse_number_input(text, "--y", kY); });
  EXPECT_EQ(m.find('\n'), std::string::npos);
  EXPECT_EQ(m.find('\x1b'), std::string::npos);
  EXPECT_NE(m.find("..."), std::string::npos);
  EXPECT_LT(m.size(), 150u);
}

TEST(NumberInput, ListKeepsEmptyFieldsAsErrors) {
  EXPECT_EQ(parse_number_list("0.001,0,-0.002", "--creepage", kY, 3), (std::vector<double>{0.001, 0.0, -0.002}));
  EXPECT_EQ(parse_number_list("0.01", "--y", kY), (std::vector<double>{0.01}));
  for (const char* text : {"", ",", "0.001,,0", "0.001,0,", ",0.001,0"}) {
    EXPECT_NE(test::error_message([&] { parse_number_list(text, "--creepage", kY, 3); }).find("empty value"), std::string::npos)
        << text;
  }
  EXPECT_NE(test::error_message([] { parse_number_list("0.001,0", "--creepage", kY, 3); }).find("takes 3"), std::string::npos);
  EXPECT_NE(test::error_message([] { parse_number_list("0.001,nan,0", "--creepage", kY, 3); }).find("value 2 of"),
            std::string::npos);
}

TEST(NumberInput, FieldsEachByTheirRule) {
  const NumberField creepage[] = {{"xi", NumberRule{-10, 10, false, ""}},
                                  {"eta", NumberRule{-10, 10, false, ""}},
                                  {"phi", NumberRule{-1000, 1000, false, "1/m"}}};
  EXPECT_EQ(parse_number_fields("0.001,0,500", "--creepage", creepage), (std::vector<double>{0.001, 0.0, 500.0}));
  EXPECT_EQ(test::error_message([&] { parse_number_fields("20,0,0", "--creepage", creepage); }),
            "--creepage: xi (value 1 of '20,0,0'): must be a number in [-10, 10], got 20");
  EXPECT_NE(test::error_message([&] { parse_number_fields("0,0,2000", "--creepage", creepage); }).find("phi"), std::string::npos);
  EXPECT_NE(test::error_message([&] { parse_number_fields("0,,0", "--creepage", creepage); }).find("empty value"),
            std::string::npos);
  EXPECT_NE(test::error_message([&] { parse_number_fields("0,0", "--creepage", creepage); }).find("takes 3"), std::string::npos);
}

TEST(NumberInput, NumbersFromPythonFollowTheSameRule) {
  const NumberRule wheel{0, 1, true, ""};
  EXPECT_EQ(number_problem(1.0, wheel), "");
  EXPECT_NE(number_problem(0.7, wheel), "");
  EXPECT_NE(number_problem(4294967296.0, wheel), "");
  EXPECT_NE(number_problem(-1.0, wheel), "");
  EXPECT_NE(number_problem(std::numeric_limits<double>::quiet_NaN(), wheel), "");
  EXPECT_EQ(test::error_message([] { check_number_input(1.7, "slot", NumberRule{0, 1, true, ""}); }),
            "slot: must be a whole number in [0, 1], got 1.7 (not a whole number)");
}

}  // namespace
}  // namespace railtab
