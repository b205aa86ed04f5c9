// SPDX-License-Identifier: Apache-2.0
// Command-line options that hold numbers, all read by core/number_input.hpp: an empty value, NaN,
// infinity, a fraction where a count is meant or a value outside the option's documented range
// is a usage error (exit 2) naming the option. The range is shown in --help.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/number_input.hpp"

namespace CLI {
class App;
class Option;
}

namespace railtab {

// --threads N: 0 (all cores) up to 1024; the sweep runs on at most the cores (effective_threads,
// engine/parallel_for.hpp). The bound keeps a typo away from oneTBB: an arena of 1e5 slots crashed
// inside its allocator.
inline constexpr int kMaxThreads = 1024;
inline constexpr NumberRule kThreadsRule{0, kMaxThreads, true, ""};
// --max-points, --max-bytes: a positive count below 2^63.
inline constexpr NumberRule kSizeLimitRule{1, 0x1p63, true, ""};

// `name` is the option's spelling ("--y"); the default, when the value has one, is shown in --help.
CLI::Option* add_number_option(CLI::App* cmd, const std::string& name, double& value, const NumberRule& rule,
                               const std::string& help);
CLI::Option* add_number_option(CLI::App* cmd, const std::string& name, std::optional<double>& value,
                               const NumberRule& rule, const std::string& help);
CLI::Option* add_count_option(CLI::App* cmd, const std::string& name, int& value, const NumberRule& rule,
                              const std::string& help);
CLI::Option* add_count_option(CLI::App* cmd, const std::string& name, std::uint64_t& value, const NumberRule& rule,
                              const std::string& help);
// One or more numbers: comma-separated, or separate arguments (--y 0.001,0.002 or --y 0.001 0.002).
CLI::Option* add_number_list_option(CLI::App* cmd, const std::string& name, std::vector<double>& values,
                                    const NumberRule& rule, const std::string& help);
// Exactly fields.size() numbers, each by its own rule (--creepage XI,ETA,PHI or XI ETA PHI).
CLI::Option* add_number_fields_option(CLI::App* cmd, const std::string& name, std::vector<double>& values,
                                      std::span<const NumberField> fields, const std::string& help);

}  // namespace railtab
