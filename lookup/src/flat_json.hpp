// SPDX-License-Identifier: Apache-2.0
// Parser for the one JSON shape the lookup reads: the root attribute fixed_axes, a flat object
// of numbers ({"roll":0.0,"load":78500.0}). Small on purpose: the lookup carries no JSON library.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace railtab::lookup::detail {

// One key of a flat object: a number, or a string (is_text).
struct FlatJsonEntry {
  std::string key;     // member name
  double number = 0;   // value when !is_text
  std::string text;    // value when is_text
  bool is_text = false;
};

// Keys and values (numbers or strings) in file order. Throws std::runtime_error saying what and
// where on anything else (nested values, arrays, trailing text).
std::vector<FlatJsonEntry> parse_flat_json(std::string_view text);

// As parse_flat_json, but every value must be a number.
std::vector<std::pair<std::string, double>> parse_flat_json_numbers(std::string_view text);

}  // namespace railtab::lookup::detail
