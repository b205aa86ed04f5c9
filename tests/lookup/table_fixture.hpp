// SPDX-License-Identifier: Apache-2.0
// Writes railtab table files (docs/table-format.md, version 1.0) filled with known functions,
// straight from the HDF5 C API: the lookup tests must not depend on the generator's writer.
// Header-only so test_lookup, the fixture-writer program and bench/lookup_bench.cpp share it.
#pragma once

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace railtab::lookup::testing {

inline const char* const kVarNames[6] = {"y", "roll", "load", "xi", "eta", "phi"};
inline const char* const kVarUnits[6] = {"m", "rad", "N", "1", "1", "rad/m"};

struct PartFormat {
  const char* name;                  // group name
  std::vector<const char*> outputs;  // float64 datasets
  std::vector<const char*> units;    // their units
  bool uses[6];                      // state variables it may be tabulated over
};

inline const std::vector<PartFormat>& part_formats() {
  static const std::vector<PartFormat> parts = {
      {"geometry",
       {"contact_angle", "rolling_radius", "wheel_y", "rail_y", "separation", "curvature_a",
        "curvature_b"},
       {"rad", "m", "m", "m", "m", "1/m", "1/m"},
       {true, true, false, false, false, false}},
      {"normal",
       {"normal_force", "approach", "area", "max_pressure", "a", "b"},
       {"N", "m", "m2", "Pa", "m", "m"},
       {true, true, true, false, false, false}},
      {"creep", {"fx", "fy", "mz", "slip_fraction"}, {"N", "N", "N m", "1"},
       {true, true, true, true, true, true}},
      {"wear", {"wear_rate"}, {"m2/m"}, {true, true, true, true, true, true}},
  };
  return parts;
}

// Value of output `output` (index in its part) of part `part` (0..3), wheel, slot, at the state
// x[0..5] (y, roll, load, xi, eta, phi; untabulated variables hold their fixed value or 0).
using ValueFn = std::function<double(int wheel, int part, int output, int slot, const double* x)>;
using StatusFn = std::function<std::uint32_t(int wheel, int part, int slot, const double* x)>;

struct FixtureSpec {
  std::vector<std::pair<int, std::vector<double>>> axes;  // (variable 0..5, nodes), in var order
  int n_slots = 2;                                        // contact slots
  std::vector<std::pair<int, double>> fixed;              // (variable, fixed value)
  std::vector<int> parts = {0, 1, 2, 3};                  // parts written
  std::string format_version = "1.0";                     // root attribute
  std::string omit_dataset;        // e.g. "/right/creep/fy": left out (bad-file tests)
  std::string wrong_axes_dataset;  // this dataset gets a wrong 'axes' attribute
  bool fixed_length_strings = false;  // fixed-length instead of variable-length string attributes
  // Format 1.1 integrity (docs/table-format.md): Fletcher32 on every dataset, checksummed
  // metadata (HDF5 1.10 file format), fixed-length strings. false: a legacy 1.0 table.
  bool checksums = true;
  // With checksums false: still the HDF5 1.10 file format (superblock 3, checksummed metadata)
  // but no Fletcher32 and any string kind, as other writers make it (h5py with libver="latest").
  // false (and checksums false): superblock 0, a format-1.0 table, which the lookup refuses.
  bool checksummed_metadata = false;
  // Variables neither on an axis nor in `fixed` (nor in fixed_text) are written to fixed_axes
  // at 0, as the generator does; false leaves them out (a malformed table).
  bool complete_fixed = true;
  std::vector<std::pair<std::string, std::string>> extra_root_attributes;  // e.g. {"shard","1/4"}
  std::string fixed_text;          // extra raw "key":value members of fixed_axes, e.g. "\"roll\":\"equilibrium\""
  bool fixed_as_datasets = false;  // format 2: fixed variables as scalar /axes/<name>, no fixed_axes JSON
  ValueFn value;                      // required
  StatusFn status = [](int, int, int, const double*) -> std::uint32_t { return 1u; };
};

namespace fixture_detail {

inline void check(herr_t r, const char* what) {
  if (r < 0) throw std::runtime_error(std::string("fixture: HDF5 call failed: ") + what);
}
inline hid_t check_id(hid_t id, const char* what) {
  if (id < 0) throw std::runtime_error(std::string("fixture: HDF5 call failed: ") + what);
  return id;
}

inline void string_attr(hid_t obj, const char* name, const std::string& value, bool fixed_len) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate(H5S_SCALAR);
  if (fixed_len) {
    H5Tset_size(type, value.empty() ? 1 : value.size());
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    const hid_t a = check_id(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), name);
    check(H5Awrite(a, type, value.empty() ? "" : value.data()), name);
    H5Aclose(a);
  } else {
    H5Tset_size(type, H5T_VARIABLE);
    const char* p = value.c_str();
    const hid_t a = check_id(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), name);
    check(H5Awrite(a, type, &p), name);
    H5Aclose(a);
  }
  H5Sclose(space);
  H5Tclose(type);
}

// Creates a dataset (chunked + shuffle + deflate 4 above 64 KiB, as the format says; with
// `checksum` every dataset is chunked, whole when small, and gets Fletcher32).
inline hid_t create_dataset(hid_t parent, const char* name, hid_t type,
                            const std::vector<hsize_t>& dims, std::size_t elem_size,
                            bool checksum) {
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  std::size_t n = 1;
  for (hsize_t d : dims) n *= d;
  if (checksum && n * elem_size <= 64 * 1024) {
    check(H5Pset_chunk(dcpl, static_cast<int>(dims.size()), dims.data()), "chunk");
  }
  if (n * elem_size > 64 * 1024) {
    std::vector<hsize_t> chunk = dims;
    // Chunk = trailing dimensions whole, leading ones 1, until ~64 KiB.
    std::size_t bytes = elem_size;
    for (int k = static_cast<int>(dims.size()) - 1; k >= 0; --k) {
      if (bytes * dims[k] > 64 * 1024) {
        chunk[k] = std::max<hsize_t>(1, (64 * 1024) / bytes);
        for (int j = k - 1; j >= 0; --j) chunk[j] = 1;
        break;
      }
      bytes *= dims[k];
    }
    check(H5Pset_chunk(dcpl, static_cast<int>(dims.size()), chunk.data()), "chunk");
    check(H5Pset_shuffle(dcpl), "shuffle");
    check(H5Pset_deflate(dcpl, 4), "deflate");
  }
  if (checksum) check(H5Pset_fletcher32(dcpl), "fletcher32");
  const hid_t d =
      check_id(H5Dcreate2(parent, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), name);
  H5Pclose(dcpl);
  H5Sclose(space);
  return d;
}

}  // namespace fixture_detail

// Writes `spec` to `path` (overwriting). Throws std::runtime_error on HDF5 failure.
inline void write_fixture(const std::string& path, const FixtureSpec& spec) {
  using namespace fixture_detail;
  const bool fl = spec.fixed_length_strings || spec.checksums;
  const bool ck = spec.checksums;
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (ck || spec.checksummed_metadata) check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_LATEST), "libver");
  const hid_t file = check_id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl),
                              path.c_str());
  H5Pclose(fapl);
  std::vector<std::pair<int, double>> fixed = spec.fixed;
  if (spec.complete_fixed) {
    for (int v = 0; v < 6; ++v) {
      bool known = spec.fixed_text.find(std::string("\"") + kVarNames[v] + "\"") != std::string::npos;
      for (const auto& a : spec.axes) known |= a.first == v;
      for (const auto& f : spec.fixed) known |= f.first == v;
      if (!known) fixed.emplace_back(v, 0.0);
    }
  }
  std::string fixed_json = "{";
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", fixed[k].second);
    if (k) fixed_json += ',';
    fixed_json += '"';
    fixed_json += kVarNames[fixed[k].first];
    fixed_json += "\":";
    fixed_json += buf;
  }
  if (!spec.fixed_text.empty()) fixed_json += (fixed.empty() ? "" : ",") + spec.fixed_text;
  fixed_json += "}";
  string_attr(file, "format_version", spec.format_version, fl);
  string_attr(file, "railtab_version", "test-fixture", fl);
  string_attr(file, "git_commit", "unknown", fl);
  string_attr(file, "created", "2024-01-01T00:00:00Z", fl);
  string_attr(file, "scene", "# fixture written by tests/lookup/table_fixture.hpp\n", fl);
  string_attr(file, "scene_name", "fixture", fl);
  string_attr(file, "models", "{}", fl);
  if (!spec.fixed_as_datasets) string_attr(file, "fixed_axes", fixed_json, fl);
  for (const auto& [name, value] : spec.extra_root_attributes)
    string_attr(file, name.c_str(), value, fl);

  // Axes as dimension scales.
  const hid_t axes = check_id(H5Gcreate2(file, "axes", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                              "axes");
  hid_t scale[7];  // per variable, [6] = slot
  for (int v = 0; v < 7; ++v) scale[v] = -1;
  double x_fixed[6] = {0, 0, 0, 0, 0, 0};
  for (const auto& [var, value] : spec.fixed) x_fixed[var] = value;
  for (const auto& [var, nodes] : spec.axes) {
    const hid_t d = create_dataset(axes, kVarNames[var], H5T_IEEE_F64LE, {nodes.size()}, 8, ck);
    check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, nodes.data()), "axis");
    check(H5DSset_scale(d, kVarNames[var]), "set_scale");
    string_attr(d, "units", kVarUnits[var], fl);
    string_attr(d, "description", std::string("axis ") + kVarNames[var], fl);
    scale[var] = d;
  }
  if (spec.fixed_as_datasets) {
    // Every fixed variable (with complete_fixed, the unlisted ones at 0 too); with checksums
    // compact, as the generator writes them (a scalar cannot be chunked for Fletcher32).
    for (const auto& [var, value] : fixed) {
      const hid_t space = H5Screate(H5S_SCALAR);
      const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
      if (ck) check(H5Pset_layout(dcpl, H5D_COMPACT), "compact");
      const hid_t d = check_id(H5Dcreate2(axes, kVarNames[var], H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                          dcpl, H5P_DEFAULT), "fixed");
      H5Pclose(dcpl);
      check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value), "fixed");
      string_attr(d, "units", kVarUnits[var], fl);
      H5Dclose(d);
      H5Sclose(space);
    }
  }
  {
    std::vector<std::int32_t> slots(static_cast<std::size_t>(spec.n_slots));
    for (int s = 0; s < spec.n_slots; ++s) slots[s] = s;
    const hid_t d = create_dataset(axes, "slot", H5T_STD_I32LE, {slots.size()}, 4, ck);
    check(H5Dwrite(d, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, slots.data()), "slot");
    check(H5DSset_scale(d, "slot"), "set_scale");
    string_attr(d, "units", "1", fl);
    string_attr(d, "description", "contact slot: 0 = tread, 1 = flange", fl);
    scale[6] = d;
  }

  const auto& formats = part_formats();
  for (int wheel = 0; wheel < 2; ++wheel) {
    const hid_t wg = check_id(H5Gcreate2(file, wheel == 0 ? "left" : "right", H5P_DEFAULT,
                                         H5P_DEFAULT, H5P_DEFAULT), "wheel");
    for (int part : spec.parts) {
      const PartFormat& pf = formats[part];
      const hid_t pg =
          check_id(H5Gcreate2(wg, pf.name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), pf.name);
      // The part's dimensions: its variables that are swept, in order, then slot.
      std::vector<int> vars;
      std::vector<const std::vector<double>*> nodes;
      std::vector<hsize_t> dims;
      std::string axes_attr;
      for (const auto& [var, n] : spec.axes) {
        if (!pf.uses[var]) continue;
        vars.push_back(var);
        nodes.push_back(&n);
        dims.push_back(n.size());
        axes_attr += std::string(kVarNames[var]) + ",";
      }
      dims.push_back(static_cast<hsize_t>(spec.n_slots));
      axes_attr += "slot";
      std::size_t n_total = 1;
      for (hsize_t d : dims) n_total *= d;

      // Grid state of every flat index (C order), slot last.
      auto state_of = [&](std::size_t flat, double* x, int& slot) {
        for (int v = 0; v < 6; ++v) x[v] = x_fixed[v];
        slot = static_cast<int>(flat % dims.back());
        flat /= dims.back();
        for (int k = static_cast<int>(vars.size()) - 1; k >= 0; --k) {
          x[vars[k]] = (*nodes[k])[flat % dims[k]];
          flat /= dims[k];
        }
      };
      const std::string group = std::string("/") + (wheel == 0 ? "left/" : "right/") + pf.name;
      auto finish = [&](hid_t d, const std::string& full, const char* units, const char* desc) {
        string_attr(d, "units", units, fl);
        string_attr(d, "description", desc, fl);
        string_attr(d, "axes", full == spec.wrong_axes_dataset ? "slot,y" : axes_attr, fl);
        for (std::size_t k = 0; k < vars.size(); ++k)
          check(H5DSattach_scale(d, scale[vars[k]], static_cast<unsigned>(k)), "attach");
        check(H5DSattach_scale(d, scale[6], static_cast<unsigned>(vars.size())), "attach slot");
        H5Dclose(d);
      };
      std::vector<double> buf(n_total);
      for (std::size_t o = 0; o < pf.outputs.size(); ++o) {
        const std::string full = group + "/" + pf.outputs[o];
        if (full == spec.omit_dataset) continue;
        for (std::size_t flat = 0; flat < n_total; ++flat) {
          double x[6];
          int slot;
          state_of(flat, x, slot);
          buf[flat] = spec.value(wheel, part, static_cast<int>(o), slot, x);
        }
        const hid_t d = create_dataset(pg, pf.outputs[o], H5T_IEEE_F64LE, dims, 8, ck);
        check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()), "write");
        finish(d, full, pf.units[o], pf.outputs[o]);
      }
      const std::string full = group + "/status";
      if (full != spec.omit_dataset) {
        std::vector<std::uint32_t> st(n_total);
        for (std::size_t flat = 0; flat < n_total; ++flat) {
          double x[6];
          int slot;
          state_of(flat, x, slot);
          st[flat] = spec.status(wheel, part, slot, x);
        }
        const hid_t d = create_dataset(pg, "status", H5T_STD_U32LE, dims, 4, ck);
        check(H5Dwrite(d, H5T_NATIVE_UINT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, st.data()), "status");
        finish(d, full, "1", "status bits (src/core/status.hpp)");
      }
      H5Gclose(pg);
    }
    H5Gclose(wg);
  }
  for (hid_t s : scale)
    if (s >= 0) H5Dclose(s);
  H5Gclose(axes);
  check(H5Fclose(file), "close");
}

// Evenly spaced nodes a .. b (n >= 2).
inline std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> x(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) x[i] = a + (b - a) * i / (n - 1);
  return x;
}

// A table of a scene's size (the shape of an earlier default scene, not of a shipped one): y 41 x
// xi 7 x eta 7 x phi 5, 2 slots, roll and load fixed; geometry and normal on y only. Smooth made-up values (the lookup does not care).
inline FixtureSpec scene_sized_spec() {
  FixtureSpec spec;
  spec.axes = {{0, linspace(-0.01, 0.01, 41)},
               {3, linspace(-0.01, 0.01, 7)},
               {4, linspace(-0.01, 0.01, 7)},
               {5, linspace(-1.0, 1.0, 5)}};
  spec.fixed = {{1, 0.0}, {2, 78500.0}};
  spec.value = [](int wheel, int part, int out, int slot, const double* x) {
    const double sign = wheel == 0 ? 1.0 : -1.0;
    return (1.0 + part + 0.1 * out + slot) *
           (sign * x[0] * 100.0 + std::sin(30.0 * x[3]) + 0.5 * x[4] * x[4] + 0.1 * x[5]);
  };
  return spec;
}

}  // namespace railtab::lookup::testing
