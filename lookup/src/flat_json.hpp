// Parser for the one JSON shape the lookup reads: the root attribute fixed_axes, a flat object
// of numbers ({"roll":0.0,"load":78500.0}). Small on purpose: the lookup carries no JSON library.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace railtab::lookup::detail {

// Keys and values in file order. Throws std::runtime_error saying what and where on anything
// else (nested values, strings as values, trailing text).
std::vector<std::pair<std::string, double>> parse_flat_json_numbers(std::string_view text);

}  // namespace railtab::lookup::detail
