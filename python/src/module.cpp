// SPDX-License-Identifier: Apache-2.0
// The compiled part of the Python package `railtab` (python/railtab/__init__.py wraps it): the
// lookup's tables, profiles from files and the direct contact models.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_railtab, m) {
  m.doc() = "railtab's compiled core; use the package `railtab`, not this module";
  railtab::python::bind_table(m);
  railtab::python::bind_profile(m);
  railtab::python::bind_evaluate(m);
  railtab::python::bind_numbers(m);
}
