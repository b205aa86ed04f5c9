// SPDX-License-Identifier: Apache-2.0
// railtab._check_number: the command line's number reader (core/number_input.hpp) for the Python
// module's arguments (railtab/_inputs.py), so both refuse the same values with the same words; and
// railtab.kalker_coefficients, the C++ table of Kalker's linear creep coefficients
// (tangential/kalker_coefficients.hpp), so that Python users take the same C11, C22, C23.
#include <pybind11/pybind11.h>

#include <string>

#include "bindings.hpp"
#include "core/number_input.hpp"
#include "tangential/kalker_coefficients.hpp"

namespace railtab::python {

void bind_numbers(pybind11::module_& m) {
  m.def(
      "_check_number",
      [](const std::string& name, double value, double min, double max, bool whole, const std::string& unit) {
        return check_number_input(value, name, NumberRule{min, max, whole, unit.c_str()});  // railtab.Error
      },
      pybind11::arg("name"), pybind11::arg("value"), pybind11::arg("min"), pybind11::arg("max"),
      pybind11::arg("whole") = false, pybind11::arg("unit") = "");
  m.def(
      "kalker_coefficients",
      [](double a_over_b, double poisson_ratio) {
        const KalkerCoefficients c = kalker_coefficients(a_over_b, poisson_ratio);  // railtab.Error
        return pybind11::make_tuple(c.c11, c.c22, c.c23);
      },
      pybind11::arg("a_over_b"), pybind11::arg("poisson_ratio"),
      "Kalker's linear creep coefficients (C11, C22, C23) [1] of an ellipse with semi-axes a (rolling\n"
      "direction) and b (lateral), a_over_b = a / b > 0, Poisson's ratio in [0, 0.5]: Table E.3 of\n"
      "Kalker (1990), interpolated as tangential/kalker_coefficients.hpp. Linear theory:\n"
      "fx = -G c^2 C11 xi, fy = -G c^2 C22 eta - G c^3 C23 phi, c^2 = a b.");
}

}  // namespace railtab::python
