// SPDX-License-Identifier: Apache-2.0
// The message of the railtab::Error that `f` throws, "" when it throws none. Tests use it to
// assert that bad input is refused with a message naming the input and the problem.
#pragma once

#include <string>

#include "core/check.hpp"

namespace railtab::test {

template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace railtab::test
