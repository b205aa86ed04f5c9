// SPDX-License-Identifier: Apache-2.0
// railtab._check_number: the command line's number reader (core/number_input.hpp) for the Python
// module's arguments (railtab/_inputs.py), so both refuse the same values with the same words.
#include <pybind11/pybind11.h>

#include <string>

#include "bindings.hpp"
#include "core/number_input.hpp"

namespace railtab::python {

void bind_numbers(pybind11::module_& m) {
  m.def(
      "_check_number",
      [](const std::string& name, double value, double min, double max, bool whole, const std::string& unit) {
        return check_number_input(value, name, NumberRule{min, max, whole, unit.c_str()});  // railtab.Error
      },
      pybind11::arg("name"), pybind11::arg("value"), pybind11::arg("min"), pybind11::arg("max"),
      pybind11::arg("whole") = false, pybind11::arg("unit") = "");
}

}  // namespace railtab::python
