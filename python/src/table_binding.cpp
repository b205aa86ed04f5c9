// SPDX-License-Identifier: Apache-2.0
// railtab.Table: a loaded lookup table and its vectorised query. The query loop runs in C++ with
// the GIL released; Python only broadcasts the inputs and names the outputs (railtab/_table.py).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "railtab/lookup.hpp"

namespace railtab::python {
namespace {

namespace py = pybind11;
namespace lk = railtab::lookup;

lk::Method parse_method(const std::string& name) {
  if (name == "linear") return lk::Method::kLinear;
  if (name == "cubic") return lk::Method::kCubic;
  if (name == "monotone-cubic") return lk::Method::kMonotoneCubic;
  throw py::value_error("method must be 'linear', 'cubic' or 'monotone-cubic', got '" + name + "'");
}

const char* method_name(lk::Method method) {
  switch (method) {
    case lk::Method::kLinear: return "linear";
    case lk::Method::kCubic: return "cubic";
    case lk::Method::kMonotoneCubic: return "monotone-cubic";
  }
  return "?";
}

using Doubles = py::array_t<double, py::array::forcecast>;
using Ints = py::array_t<std::int32_t, py::array::forcecast>;

// One state variable of the query: n values, or one value for every state. Strided access
// (no copy of a numpy view); `stride` 0 repeats the one value.
struct Column {
  const char* base = nullptr;
  py::ssize_t stride = 0;
  double at(py::ssize_t k) const { return *reinterpret_cast<const double*>(base + k * stride); }
};

Column column(const Doubles& a, py::ssize_t n, const char* name) {
  if (a.ndim() != 1 || (a.shape(0) != n && a.shape(0) != 1)) {
    throw py::value_error(std::string(name) + ": expected 1 or " + std::to_string(n) + " values");
  }
  return {reinterpret_cast<const char*>(a.data()), a.shape(0) == 1 ? 0 : a.strides(0)};
}

// A numpy array on memory from operator new, not numpy's allocator: numpy advises the kernel to
// back large arrays with huge pages, and on a busy machine the kernel then spends more time
// compacting and zeroing them than the query itself takes (measured: 1.1 us against 0.75 us per
// state for 1e6 states, python/bench/query_bench.py). The array owns the memory (capsule).
template <class T>
py::array_t<T> uninitialised(std::vector<py::ssize_t> shape) {
  py::ssize_t n = 1;
  for (py::ssize_t e : shape) n *= e;
  T* data = new T[static_cast<std::size_t>(std::max<py::ssize_t>(n, 1))];
  py::capsule owner(data, [](void* p) { delete[] static_cast<T*>(p); });
  return py::array_t<T>(shape, data, owner);
}

// Queries n states. Inputs are 1-D arrays of length n or 1; `slot` < 0: every slot, else that
// slot only (Table::query_slot, about half the cost). Returns (values [n, slots, outputs],
// part_status [n, slots, parts], status [n, slots], derivatives) with slots = n_slots or 1;
// `derivatives`: None, or with want_derivatives (Table::query_derivatives, or with a slot
// Table::query_slot_derivatives) d output / d variable
// [n, slots, outputs, variables] (variables y, roll, load, xi, eta, phi, yaw); `track`: None, or with
// want_track_forces (every slot only; lk::track_forces) the pair (per slot [n, slots, 3]: lateral,
// vertical [N], contact angle [rad]; per wheel [n, 5]: wheel_lateral, wheel_vertical, Y, Q [N], Y/Q);
// `coefficients`: None, or with want_creep_coefficients (Table::query_creep_coefficients) the
// linear creep coefficients [n, slots, 9] (force-major: fx, fy, mz by xi, eta, phi).
py::tuple query_arrays(const lk::Table& table, py::ssize_t n, const Ints& wheel, const Doubles& y,
                       const Doubles& roll, const Doubles& load, const Doubles& xi, const Doubles& eta,
                       const Doubles& phi, const Doubles& yaw, int slot, bool want_derivatives, bool want_track_forces,
                       bool want_creep_coefficients) {
  if (n < 0) throw py::value_error("n must be >= 0");
  if (wheel.ndim() != 1 || (wheel.shape(0) != n && wheel.shape(0) != 1)) {
    throw py::value_error("wheel: expected 1 or " + std::to_string(n) + " values");
  }
  if (slot >= table.n_slots()) {
    throw py::value_error("slot " + std::to_string(slot) + " out of range: the table has " +
                          std::to_string(table.n_slots()) + " slots");
  }
  const std::array<Column, 7> in{column(y, n, "y"),   column(roll, n, "roll"), column(load, n, "load"),
                                 column(xi, n, "xi"), column(eta, n, "eta"),   column(phi, n, "phi"),
                                 column(yaw, n, "yaw")};
  const std::int32_t* wheels = wheel.data();
  const py::ssize_t wheel_step = wheel.shape(0) == 1 ? 0 : 1;
  for (py::ssize_t k = 0; k < wheel.shape(0); ++k) {
    if (wheels[k] != 0 && wheels[k] != 1) throw py::value_error("wheel must be 0 (left) or 1 (right)");
  }
  if (want_derivatives && !table.derivatives_supported())
    throw py::value_error("derivatives=True needs a table loaded with method 'linear' or 'cubic', not '" +
                          std::string(method_name(table.method())) + "' (its limited slopes are not differentiated)");
  if (want_track_forces && slot >= 0)
    throw py::value_error("track_forces=True sums the forces of every slot: leave slot out");
  if (want_creep_coefficients && !table.has_creep_coefficients())
    throw py::value_error("creep_coefficients=True: " + table.path() + " holds no linear creep coefficients (format " +
                          table.format_version() + "; they are stored since format 2.3): regenerate it with "
                          "railtab generate");
  const py::ssize_t slots = slot < 0 ? table.n_slots() : 1;
  py::object coefficient_array = py::none();
  double* kv = nullptr;
  if (want_creep_coefficients) {
    auto a = uninitialised<double>({n, slots, 9});
    kv = a.mutable_data();
    coefficient_array = a;
  }
  py::object track_array = py::none();
  double* tv = nullptr;
  double* tw = nullptr;
  if (want_track_forces) {
    auto per_slot = uninitialised<double>({n, slots, 3});
    auto per_wheel = uninitialised<double>({n, 5});
    tv = per_slot.mutable_data();
    tw = per_wheel.mutable_data();
    track_array = py::make_tuple(per_slot, per_wheel);
  }
  constexpr py::ssize_t kVars = lk::kNumVariables;
  py::object derivative_array = py::none();
  double* dv = nullptr;
  if (want_derivatives) {
    auto a = uninitialised<double>({n, slots, static_cast<py::ssize_t>(lk::kNumOutputs), kVars});
    dv = a.mutable_data();
    derivative_array = a;
  }
  auto values = uninitialised<double>({n, slots, static_cast<py::ssize_t>(lk::kNumOutputs)});
  auto part_status = uninitialised<std::uint32_t>({n, slots, static_cast<py::ssize_t>(lk::kNumParts)});
  auto status = uninitialised<std::uint32_t>({n, slots});
  double* v = values.mutable_data();
  std::uint32_t* ps = part_status.mutable_data();
  std::uint32_t* st = status.mutable_data();
  {
    py::gil_scoped_release release;
    lk::State s = table.default_state();
    lk::Result r;
    lk::Contact c;
    lk::Derivatives d;
    lk::SlotDerivatives sd;
    lk::CreepCoefficients cc;
    for (py::ssize_t k = 0; k < n; ++k) {
      s.y = in[0].at(k);
      s.roll = in[1].at(k);
      s.load = in[2].at(k);
      s.xi = in[3].at(k);
      s.eta = in[4].at(k);
      s.phi = in[5].at(k);
      s.yaw = in[6].at(k);
      const auto w = static_cast<lk::Wheel>(wheels[k * wheel_step]);
      const lk::Contact* contacts = &c;
      if (dv && slot >= 0) {
        table.query_slot_derivatives(w, s, slot, c, sd);
        std::copy_n(&sd.d[0][0], lk::kNumOutputs * kVars, dv);
        dv += lk::kNumOutputs * kVars;
      } else if (dv) {
        table.query_derivatives(w, s, r, d);
        contacts = r.contact;
        for (py::ssize_t j = 0; j < slots; ++j) {
          std::copy_n(&d.d[j][0][0], lk::kNumOutputs * kVars, dv);
          dv += lk::kNumOutputs * kVars;
        }
      } else if (slot < 0) {
        table.query(w, s, r);
        contacts = r.contact;
      } else {
        table.query_slot(w, s, slot, c);
      }
      if (kv) {
        table.query_creep_coefficients(w, s, cc);
        for (py::ssize_t j = 0; j < slots; ++j) {
          std::copy_n(&cc.k[std::max(slot, 0) + j][0][0], 9, kv);
          kv += 9;
        }
      }
      if (tv) {  // slot < 0 here: `r` holds every slot
        const lk::TrackForces f = lk::track_forces(w, r);
        for (py::ssize_t j = 0; j < slots; ++j) {
          *tv++ = f.lateral[j];
          *tv++ = f.vertical[j];
          *tv++ = f.contact_angle[j];
        }
        *tw++ = f.wheel_lateral;
        *tw++ = f.wheel_vertical;
        *tw++ = f.y_force;
        *tw++ = f.q_force;
        *tw++ = f.y_over_q;
      }
      for (py::ssize_t j = 0; j < slots; ++j) {
        std::copy_n(contacts[j].value, lk::kNumOutputs, v);
        std::copy_n(contacts[j].part_status, lk::kNumParts, ps);
        *st++ = contacts[j].status;
        v += lk::kNumOutputs;
        ps += lk::kNumParts;
      }
    }
  }
  return py::make_tuple(values, part_status, status, derivative_array, track_array, coefficient_array);
}

}  // namespace

void bind_table(py::module_& m) {
  py::class_<lk::Table>(m, "Table")
      .def_static(
          "load",
          [](const std::string& path, const std::string& method) {
            // HDF5 takes a C string: a NUL would cut the name and open another file.
            if (path.find('\0') != std::string::npos) throw py::value_error("path contains a NUL character: not a file name");
            try {
              return lk::Table::load(path, {parse_method(method)});
            } catch (const lk::LoadError& e) {
              // OSError for "cannot use this file": the message names the file and the problem.
              PyErr_SetString(PyExc_OSError, e.what());
              throw py::error_already_set();
            }
          },
          py::arg("path"), py::arg("method") = "linear")
      .def_property_readonly("path", &lk::Table::path)
      .def_property_readonly("method", [](const lk::Table& t) { return method_name(t.method()); })
      .def_property_readonly("n_slots", &lk::Table::n_slots)
      .def_property_readonly("parts",
                             [](const lk::Table& t) {
                               py::list parts;
                               for (int p = 0; p < lk::kNumParts; ++p)
                                 if (t.has_part(static_cast<lk::Part>(p)))
                                   parts.append(lk::part_name(static_cast<lk::Part>(p)));
                               return parts;
                             })
      .def_property_readonly("axes",
                             [](const lk::Table& t) {
                               py::dict axes;  // insertion order = file order
                               for (const lk::AxisInfo& a : t.axes())
                                 axes[py::str(a.name)] = py::array_t<double>(a.nodes.size(), a.nodes.data());
                               return axes;
                             })
      .def_property_readonly("fixed_axes",
                             [](const lk::Table& t) {
                               py::dict fixed;
                               for (const auto& [name, value] : t.fixed_axes()) fixed[py::str(name)] = value;
                               return fixed;
                             })
      .def_property_readonly("format_version", &lk::Table::format_version)
      .def_property_readonly("scene_name", &lk::Table::scene_name)
      .def_property_readonly("memory_bytes", &lk::Table::memory_bytes)
      .def_property_readonly("has_creep_coefficients", &lk::Table::has_creep_coefficients)
      .def_property_readonly("yaw_even", &lk::Table::yaw_even)
      .def_property_readonly("has_error_map", &lk::Table::has_error_map)
      .def(
          "error_estimate",
          // The stored error map's region holding y (format 2.3), as a dict; None without one.
          [](const lk::Table& t, double y, int slot) -> py::object {
            lk::ErrorEstimate e;
            if (!t.error_estimate(y, slot, e)) return py::none();
            static constexpr const char* kNames[lk::kErrorQuantities] = {"fx", "fy", "mz", "normal_force",
                                                                         "contact_angle"};
            auto stats = [](const lk::ErrorStats& s) {
              py::dict d;
              d["samples"] = s.samples;
              for (int q = 0; q < lk::kErrorQuantities; ++q) {
                d[py::str(std::string(kNames[q]) + "_rms")] = s.rms[q];
                d[py::str(std::string(kNames[q]) + "_max")] = s.max[q];
              }
              return d;
            };
            py::dict out;
            out["y_band"] = py::make_tuple(e.y_band_start, e.y_band_end);
            out["table_vs_model"] = stats(e.table_vs_model);
            out["model_vs_exact"] = e.exact_measured ? py::object(stats(e.model_vs_exact))
                                    : e.same_model  ? py::object(py::str("same model"))
                                                    : py::object(py::none());
            return out;
          },
          py::arg("y"), py::arg("slot"))
      .def("_query_arrays", &query_arrays, py::arg("n"), py::arg("wheel"), py::arg("y"), py::arg("roll"), py::arg("load"),
           py::arg("xi"), py::arg("eta"), py::arg("phi"), py::arg("yaw"), py::arg("slot"), py::arg("derivatives") = false,
           py::arg("track_forces") = false, py::arg("creep_coefficients") = false);

  py::list outputs;
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    const auto out = static_cast<lk::Output>(o);
    outputs.append(py::make_tuple(lk::output_name(out), lk::part_name(lk::output_part(out))));
  }
  m.attr("OUTPUTS") = outputs;  // (name, part) in Contact::value order
  py::list parts;
  for (int p = 0; p < lk::kNumParts; ++p) parts.append(lk::part_name(static_cast<lk::Part>(p)));
  m.attr("PARTS") = parts;
}

}  // namespace railtab::python
