// SPDX-License-Identifier: Apache-2.0
// One function per bound area, each in its own file (module.cpp calls them in order).
#pragma once

#include <pybind11/pybind11.h>

namespace railtab::python {

void bind_table(pybind11::module_& m);     // table_binding.cpp: lookup::Table, vectorised query
void bind_profile(pybind11::module_& m);   // profile_binding.cpp: profiles from files, SIMPACK writer
void bind_evaluate(pybind11::module_& m);  // evaluate_binding.cpp: the direct models (railtab eval)
void bind_numbers(pybind11::module_& m);   // number_binding.cpp: the one number reader's checks

}  // namespace railtab::python
