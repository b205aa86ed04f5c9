// SPDX-License-Identifier: Apache-2.0
// Always-on precondition checks. A failed check throws railtab::Error with a message that names
// the input and the offending values; assert() stays for internal invariants only.
#pragma once

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace railtab {

// The one exception type of the core library: bad input, never a bug.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace railtab

// RAILTAB_CHECK(cond, "format {}", args...): throw railtab::Error unless cond holds.
#define RAILTAB_CHECK(cond, ...)                                    \
  do {                                                              \
    if (!(cond)) throw ::railtab::Error(::fmt::format(__VA_ARGS__)); \
  } while (false)
