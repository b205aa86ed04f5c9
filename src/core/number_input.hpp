// SPDX-License-Identifier: Apache-2.0
// The one reader of numbers typed by a user (every command-line option, the Python module): a
// value is one finite number in its documented range, whole where a count or index is meant.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace railtab {

// What a numeric input may hold.
struct NumberRule {
  double min = 0.0;        // smallest allowed value
  double max = 0.0;        // largest allowed value
  bool whole = false;      // a count or an index: no fraction
  const char* unit = "";   // SI unit for messages ("m", "N"; "" for none)
};

// What is wrong with `text` as a value of `rule` ("" when nothing, then `value` holds it). Text
// is refused when empty, not a number as a whole (std::from_chars; one leading '+' allowed, no
// spaces), NaN or infinite, fractional for a whole rule, or outside [min, max].
std::string number_problem(std::string_view text, const NumberRule& rule, double& value);

// The same checks for a value that is already a number (a Python argument).
std::string number_problem(double value, const NumberRule& rule);

// `text` parsed by `rule`; throws railtab::Error "NAME: problem" otherwise.
double parse_number_input(std::string_view text, std::string_view name, const NumberRule& rule);

// A comma-separated list, every field by `rule` (an empty field is refused, not skipped);
// `count` > 0 asks for exactly that many. Throws railtab::Error naming `name` and the field.
std::vector<double> parse_number_list(std::string_view text, std::string_view name, const NumberRule& rule,
                                      std::size_t count = 0);

// One field of a fixed comma-separated list: its name and its rule.
struct NumberField {
  const char* name;  // e.g. "phi"
  NumberRule rule;
};

// A comma-separated list of exactly fields.size() numbers, field k by fields[k].rule; throws
// railtab::Error "NAME: FIELD: problem" (or the count) otherwise.
std::vector<double> parse_number_fields(std::string_view text, std::string_view name,
                                        std::span<const NumberField> fields);

// `value` checked by `rule`; throws railtab::Error "NAME: problem" otherwise.
double check_number_input(double value, std::string_view name, const NumberRule& rule);

// "in [a, b] unit" / "a whole number in [a, b]": the rule's requirement, for help texts.
std::string describe(const NumberRule& rule);

}  // namespace railtab
