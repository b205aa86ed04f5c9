// SPDX-License-Identifier: Apache-2.0
// Loading a table file into the query layout (table_load.hpp).
#include "table_load.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <stdexcept>

#include "flat_json.hpp"
#include "hdf5_file.hpp"
#include "interpolate.hpp"
#include "low_confidence.hpp"
#include "part_spec.hpp"

namespace railtab::lookup::detail {
namespace {

// Format major versions this reader understands. 2 differs from 1 in how fixed variables are
// stored (scalar datasets /axes/<name> instead of the JSON root attribute fixed_axes, roll
// following the equilibrium as the root attribute roll_mode) and always carries checksums
// (docs/table-format.md, "Version history").
constexpr int kOldestMajor = 1;
constexpr int kNewestMajor = 2;
// Limits (docs/table-format.md, "Limits"), checked before anything is allocated: the generator
// writes at most 1e6 nodes per axis; one part's grid at most 2^28 nodes (2 GiB per output
// dataset and slot).
constexpr std::size_t kMaxAxisNodes = 1'000'000;
constexpr std::size_t kMaxTableValues = std::size_t{1} << 28;

std::string without_spaces(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != ' ') out += c;
  return out;
}

// "MAJOR.MINOR", both plain decimal numbers of at most 6 digits, nothing else.
bool parse_version(const std::string& v, int& major, int& minor) {
  const std::size_t dot = v.find('.');
  if (dot == std::string::npos || dot == 0 || dot > 6 || v.size() - dot - 1 == 0 ||
      v.size() - dot - 1 > 6)
    return false;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (i != dot && (v[i] < '0' || v[i] > '9')) return false;
  major = std::stoi(v.substr(0, dot));
  minor = std::stoi(v.substr(dot + 1));
  return true;
}

// Returns the major version.
int read_version(const Hdf5File& f, TableData& d) {
  const auto v = f.string_attribute("/", "format_version");
  if (!v) f.fail("missing root attribute format_version (not a railtab table?)");
  d.format_version = *v;
  int major = -1, minor = -1;
  if (!parse_version(*v, major, minor))
    f.fail("format_version '" + *v + "' is not of the form MAJOR.MINOR (e.g. \"1.1\")");
  if (major < kOldestMajor || major > kNewestMajor)
    f.fail("unsupported format_version '" + *v + "': this reader knows major versions " +
           std::to_string(kOldestMajor) + " to " + std::to_string(kNewestMajor) +
           " (a newer railtab may read it)");
  // Format 2 was never written without checksums: one without is damaged or crafted.
  if (major >= 2 && !d.checksums_verified)
    f.fail("format_version '" + *v + "' but no checksums (every format-2 table carries them)");
  // Format 2.1 and later: written by railtab generate under load control, so the low_confidence
  // rules that trust the physics apply (older and synthetic test tables need not hold physical values).
  d.load_controlled = major > 2 || (major == 2 && minor >= 1);
  return major;
}

// A shard (`railtab generate --shard I/N`) covers part of y only: refused, it must be merged.
void refuse_shard(const Hdf5File& f) {
  if (!f.has_attribute("/", "shard")) return;
  const auto which = f.string_attribute("/", "shard");
  f.fail("it is shard " + which.value_or("?") + " of a table (root attribute 'shard'): join the " +
         "shards with `railtab merge` and load the merged table");
}

// Checksums (docs/table-format.md, "Integrity"): a table either carries HDF5's Fletcher32
// filter on every dataset and checksummed metadata (superblock >= 2), or is a legacy table
// without any (loaded, flagged unverified, unless the caller requires checksums).
void read_integrity(Hdf5File& f, TableData& d, const LoadOptions& options) {
  if (!f.exists("/axes/slot")) f.fail("missing dataset /axes/slot");
  d.checksums_verified = f.checksummed("/axes/slot");
  if (d.checksums_verified) {
    if (f.superblock_version() < 2)
      f.fail("datasets carry checksums but the metadata do not (HDF5 superblock version " +
             std::to_string(f.superblock_version()) + ", checksummed metadata need >= 2)");
  } else if (options.require_checksums) {
    f.fail("it has no checksums (a table written before format 1.1): regenerate it, or load it "
           "without require_checksums");
  }
  f.set_allow_variable_strings(!d.checksums_verified);
}

void check_checksum(const Hdf5File& f, const TableData& d, const std::string& ds, bool has) {
  if (has != d.checksums_verified)
    f.fail(has ? "dataset " + ds + " has a checksum but /axes/slot has none"
               : "dataset " + ds + " has no checksum but /axes/slot has one (a checksummed " +
                     "table checksums every dataset)");
}

// An axis the query path can use: finite nodes, strictly increasing, every cell width and its
// reciprocal finite (a subnormal width has an infinite reciprocal), and the mean spacing too
// (the uniform-axis fast path multiplies by its reciprocal).
void check_axis(const Hdf5File& f, const std::string& name, const std::vector<double>& x) {
  if (x.size() < 2) f.fail("axis " + name + " has fewer than 2 nodes");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) f.fail("axis " + name + " holds a non-finite node");
    if (i > 0 && !(x[i] > x[i - 1]))
      f.fail("axis " + name + " is not strictly increasing at index " + std::to_string(i));
    if (i > 0 && !(std::isfinite(x[i] - x[i - 1]) && std::isfinite(1.0 / (x[i] - x[i - 1]))))
      f.fail("axis " + name + " has a cell width (index " + std::to_string(i - 1) + " to " +
             std::to_string(i) + ") whose reciprocal is not finite");
  }
  const double h = (x.back() - x.front()) / static_cast<double>(x.size() - 1);
  if (!(std::isfinite(h) && h > 0.0 && std::isfinite(1.0 / h)))
    f.fail("axis " + name + " has a mean spacing whose reciprocal is not finite");
}

void read_axes(const Hdf5File& f, TableData& d, int major) {
  if (!f.exists("/axes")) f.fail("missing group /axes");
  for (const int var : kFileOrder) {
    const std::string name = std::string("/axes/") + var_name(var);
    if (!f.exists(name)) continue;
    auto a = f.read_axis(name, kMaxAxisNodes, /*allow_scalar=*/major >= 2);
    if (a.dims.empty()) {  // format 2: a scalar dataset is a fixed variable
      // A scalar cannot be chunked, so it carries no Fletcher32: it is compact, its value
      // inside its object header, which the HDF5 1.10 format checksums.
      if (!a.compact) f.fail("fixed variable " + name + " is not stored compact (a format-2 scalar is)");
      if (!std::isfinite(a.values[0])) f.fail("fixed variable " + name + " is not finite");
      d.fixed[var] = true;
      d.fixed_value[var] = a.values[0];
      d.fixed_list.emplace_back(var_name(var), a.values[0]);
      continue;
    }
    check_checksum(f, d, name, a.checksummed);
    if (a.dims.size() != 1) f.fail("axis " + name + " is not 1-D, shape " + shape_text(a.dims));
    check_axis(f, name, a.values);
    d.tabulated[var] = true;
    d.axes_info.push_back({var_name(var), a.values, f.string_attribute(name, "units").value_or("")});
    d.axis[var] = Axis(std::move(a.values));
  }
  const auto slot = f.read_int32("/axes/slot", kMaxAxisNodes);
  check_checksum(f, d, "/axes/slot", slot.checksummed);
  if (slot.dims.size() != 1 || slot.values.empty())
    f.fail("axis /axes/slot must be 1-D and non-empty, shape " + shape_text(slot.dims));
  for (std::size_t i = 0; i < slot.values.size(); ++i)
    if (slot.values[i] != static_cast<std::int32_t>(i))
      f.fail("axis /axes/slot must hold 0..n-1, index " + std::to_string(i) + " holds " +
             std::to_string(slot.values[i]));
  if (slot.values.size() > static_cast<std::size_t>(kMaxSlots))
    f.fail("table has " + std::to_string(slot.values.size()) + " contact slots, the lookup " +
           "supports at most " + std::to_string(kMaxSlots));
  d.n_slots = static_cast<int>(slot.values.size());
}

void read_fixed_axes(const Hdf5File& f, TableData& d) {
  const auto text = f.string_attribute("/", "fixed_axes");
  if (!text) f.fail("missing root attribute fixed_axes");
  std::vector<FlatJsonEntry> entries;
  try {
    entries = parse_flat_json(*text);
  } catch (const std::runtime_error& e) {
    f.fail(std::string("root attribute fixed_axes is not a flat JSON object: ") + e.what());
  }
  bool listed[kNumVars] = {};
  for (const FlatJsonEntry& e : entries) {
    int var = 0;
    while (var < kNumVars && e.key != var_name(var)) ++var;
    if (var == kNumVars)
      f.fail("root attribute fixed_axes names '" + e.key + "', not a state variable (y, roll, " +
             "yaw, load, xi, eta, phi)");
    if (listed[var]) f.fail("root attribute fixed_axes lists '" + e.key + "' twice");
    listed[var] = true;
    if (d.tabulated[var]) f.fail("'" + e.key + "' is both an axis and in fixed_axes");
    if (e.is_text) {
      // Roll may follow the kinematic equilibrium at each y (root dataset /equilibrium_roll):
      // then it is neither an axis nor an input (queries must leave State::roll at 0).
      if (e.key == "roll" && e.text == "equilibrium") {
        d.roll_equilibrium = true;
        continue;
      }
      f.fail("fixed_axes value of '" + e.key + "' must be a number (or \"equilibrium\" for roll), got \"" +
             e.text + "\"");
    }
    if (!std::isfinite(e.number)) f.fail("fixed_axes value of '" + e.key + "' is not finite");
    d.fixed[var] = true;
    d.fixed_value[var] = e.number;
    d.fixed_list.emplace_back(e.key, e.number);
  }
  // Every state variable is either tabulated or fixed: a table that says nothing about one
  // cannot tell the caller what value its numbers hold for.
  d.yaw_absent = !d.tabulated[kVarYaw] && !listed[kVarYaw];  // format 1 knows no yaw
  for (int var = 0; var < kNumVars; ++var)
    if (!d.tabulated[var] && !listed[var] && var != kVarYaw)
      f.fail(std::string("state variable '") + var_name(var) + "' is neither an axis (/axes/" +
             var_name(var) + ") nor in the root attribute fixed_axes");
}

// Format 2: /axes holds the slot axis and one dataset per state variable, an axis or a scalar;
// roll may instead follow the equilibrium (root attribute roll_mode = "equilibrium"). Every
// state variable must be accounted for, as with format 1's fixed_axes.
void check_fixed_variables(const Hdf5File& f, TableData& d) {
  if (f.has_attribute("/", "fixed_axes"))
    f.fail("root attribute fixed_axes in a format-2 table (format 2 stores fixed variables as "
           "scalar datasets /axes/<name>)");
  for (const std::string& member : f.members("/axes")) {
    int var = 0;
    while (var < kNumVars && member != var_name(var)) ++var;
    if (var == kNumVars && member != "slot")
      f.fail("/axes/" + member + " is not a state variable (y, roll, yaw, load, xi, eta, phi) nor slot");
  }
  if (const auto mode = f.string_attribute("/", "roll_mode")) {
    if (*mode != "equilibrium")
      f.fail("root attribute roll_mode is '" + *mode + "' (the only mode is \"equilibrium\")");
    if (d.tabulated[kVarRoll] || d.fixed[kVarRoll])
      f.fail("roll_mode = \"equilibrium\" but /axes/roll exists too");
    d.roll_equilibrium = true;
  }
  // Yaw may be absent (a table of a scene without yaw, or older than format 2.4): computed at yaw 0.
  d.yaw_absent = !d.tabulated[kVarYaw] && !d.fixed[kVarYaw];
  // A symmetric yaw axis stored as its non-negative half (every output even in yaw): queried at |yaw|.
  if (const auto symmetry = f.string_attribute("/", "yaw_symmetry")) {
    if (*symmetry != "even")
      f.fail("root attribute yaw_symmetry is '" + *symmetry + "' (the only symmetry is \"even\")");
    if (!d.tabulated[kVarYaw] || d.axis[kVarYaw].node_vector().front() != 0.0)
      f.fail("yaw_symmetry = \"even\" needs a yaw axis starting at 0 (/axes/yaw holds the non-negative half)");
    d.yaw_even = true;
  }
  for (int var = 0; var < kNumVars; ++var)
    if (!d.tabulated[var] && !d.fixed[var] && !(var == kVarRoll && d.roll_equilibrium) && !(var == kVarYaw && d.yaw_absent))
      f.fail(std::string("state variable '") + var_name(var) + "' is neither an axis nor a fixed " +
             "value (dataset /axes/" + var_name(var) + ")");
}

// One part of one wheel as read from the file, checked.
struct PartArrays {
  std::vector<int> vars;                     // its tabulated axes (Var), file order
  std::vector<hsize_t> dims;                 // their sizes
  std::size_t nodes = 1;                     // grid nodes (product of dims)
  std::vector<std::vector<double>> outputs;  // [output][node * n_slots + slot]
  std::vector<int> output_of;                // Output of each of them
  std::vector<std::uint32_t> status;         // [node * n_slots + slot]
};

PartArrays read_part(const Hdf5File& f, const TableData& d, const std::string& group,
                     const PartSpec& spec) {
  PartArrays p;
  std::string axes_attr;
  for (const int var : kFileOrder) {
    if (!spec.uses[var] || !d.tabulated[var]) continue;
    p.vars.push_back(var);
    p.dims.push_back(static_cast<hsize_t>(d.axis[var].size()));
    p.nodes *= static_cast<std::size_t>(d.axis[var].size());  // axes <= kMaxAxisNodes: no wrap
    if (p.nodes > kMaxTableValues)
      f.fail("part " + group + " spans more than " + std::to_string(kMaxTableValues) +
             " grid nodes (limit, docs/table-format.md)");
    axes_attr += std::string(var_name(var)) + ",";
  }
  std::vector<hsize_t> expected = p.dims;
  expected.push_back(static_cast<hsize_t>(d.n_slots));
  axes_attr += "slot";

  auto check_axes_attribute = [&](const std::string& ds) {
    const auto attr = f.string_attribute(ds, "axes");
    if (!attr) f.fail("dataset " + ds + " has no 'axes' attribute");
    if (without_spaces(*attr) != axes_attr)
      f.fail("dataset " + ds + " has axes='" + *attr + "', expected '" + axes_attr + "'");
  };
  const std::string shape_source = "the table's axes (" + axes_attr + ")";
  // Format 2.1 normalised creep part: fx, fy, mz stored as <name>_normalised (creep_map.hpp).
  const bool normalised_creep = std::string(spec.name) == "creep" && f.has_attribute("/", "creep_map");
  for (int k = 0; k < spec.n_out; ++k) {
    const int o = spec.first_output + k;
    const std::string ds = group + "/" + output_name(static_cast<Output>(o)) +
                           (normalised_creep && o <= kMz ? "_normalised" : "");
    auto v = f.read_doubles(ds, expected, shape_source);
    check_checksum(f, d, ds, v.checksummed);
    check_axes_attribute(ds);
    for (std::size_t i = 0; i < v.values.size(); ++i)
      if (!std::isfinite(v.values[i]))
        f.fail("dataset " + ds + " holds a non-finite value at flat index " + std::to_string(i) +
               " (format 1.0: a cell without contact holds 0)");
    p.outputs.push_back(std::move(v.values));
    p.output_of.push_back(spec.first_output + k);
  }
  // The creep part's per-creepage normal force (load coupling, formats 1.1/1.2 and 2.x): served as
  // kNormalForce in place of the normal part's creepage-free one (it scales the normalised forces
  // of format 2.1, and a simulation needs the N that goes with fx, fy). Approach, area and
  // max_pressure stay the normal part's: one more value per record instead of four (speed).
  if (std::string(spec.name) == "creep" && f.exists(group + "/normal_force")) {
    for (int o = kNormalForce; o <= kNormalForce; ++o) {
      const std::string extra = group + "/" + output_name(static_cast<Output>(o));
      auto v = f.read_doubles(extra, expected, shape_source);
      check_checksum(f, d, extra, v.checksummed);
      check_axes_attribute(extra);
      for (std::size_t i = 0; i < v.values.size(); ++i)
        if (!std::isfinite(v.values[i]))
          f.fail("dataset " + extra + " holds a non-finite value at flat index " + std::to_string(i));
      p.outputs.push_back(std::move(v.values));
      p.output_of.push_back(o);
    }
  }
  const std::string ds = group + "/status";
  auto st = f.read_uint32(ds, expected, shape_source);
  check_checksum(f, d, ds, st.checksummed);
  check_axes_attribute(ds);
  p.status = std::move(st.values);
  return p;
}

// The creep_map keys this reader applies that a table may require (in creep_map's coordinates):
// tables whose forces are wrong without them (docs/table-format.md, "Normalised creep part").
constexpr const char* kRequirableCreepMapKeys[] = {"law_spin"};

// Format 2.1 normalised creep coordinates (creep_map.hpp): the root attribute creep_map (flat
// JSON: coordinates = "normalised", friction, <axis>_min/_max of every swept creepage axis), the
// v axes ([-1, 1]) and the normal part's scales creep_scale_xi/_eta/_phi (finite, > 0).
void read_creep_map(const Hdf5File& f, TableData& d) {
  const auto text = f.string_attribute("/", "creep_map");
  if (!text) return;
  std::vector<FlatJsonEntry> entries;
  try {
    entries = parse_flat_json(*text);
  } catch (const std::runtime_error& e) {
    f.fail(std::string("root attribute creep_map is not a flat JSON object: ") + e.what());
  }
  auto number = [&](const std::string& key) {
    for (const FlatJsonEntry& e : entries)
      if (e.key == key && !e.is_text && std::isfinite(e.number)) return e.number;
    f.fail("root attribute creep_map has no finite number '" + key + "'");
  };
  // coordinates: "normalised", then "+<key>" for each key the reader must apply to read the forces
  // right (a reader from before the key refuses the table instead of misreading it).
  std::string coordinates;
  for (const FlatJsonEntry& e : entries)
    if (e.key == "coordinates" && e.is_text) coordinates = e.text;
  const std::string base = "normalised";
  if (coordinates.compare(0, base.size(), base) != 0 || (coordinates.size() > base.size() && coordinates[base.size()] != '+'))
    f.fail("root attribute creep_map: coordinates must be \"normalised\", optionally followed by +<key> for each "
           "key the table requires");
  for (std::size_t at = base.size(); at < coordinates.size();) {
    const std::size_t end = std::min(coordinates.find('+', at + 1), coordinates.size());
    const std::string key = coordinates.substr(at + 1, end - at - 1);
    if (std::find(std::begin(kRequirableCreepMapKeys), std::end(kRequirableCreepMapKeys), key) ==
        std::end(kRequirableCreepMapKeys))
      f.fail("root attribute creep_map: the table requires key '" + key +
             "', which this reader does not know (the table is newer than this railtab: read it with a newer one)");
    if (std::none_of(entries.begin(), entries.end(), [&](const FlatJsonEntry& e) { return e.key == key; }))
      f.fail("root attribute creep_map: coordinates require key '" + key + "', which is missing");
    at = end;
  }
  for (const FlatJsonEntry& e : entries)
    if (e.key == "normal_force") {
      if (!e.is_text || e.text != "vertical_share")
        f.fail("root attribute creep_map: normal_force must be \"vertical_share\"");
      d.creep_map.vertical_share = true;
    }
  CreepMap& m = d.creep_map;
  m.friction = number("friction");
  if (!(m.friction > 0.0)) f.fail("root attribute creep_map: friction must be > 0");
  for (const FlatJsonEntry& e : entries)  // optional: the law's spin weight (absent in tables before it: 0)
    if (e.key == "law_spin") m.law_spin = number(e.key);
  if (!(m.law_spin >= 0.0)) f.fail("root attribute creep_map: law_spin must be >= 0");
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    const int var = kVarXi + k;
    m.swept[k] = d.tabulated[var];
    if (!m.swept[k]) continue;
    any = true;
    m.lo[k] = number(std::string(var_name(var)) + "_min");
    m.hi[k] = number(std::string(var_name(var)) + "_max");
    if (!(m.lo[k] < m.hi[k]))
      f.fail(std::string("root attribute creep_map: ") + var_name(var) + "_min is not below " + var_name(var) +
             "_max");
    double knee = 1.0;  // optional: the node map's knee (absent in tables before it: 1)
    for (const FlatJsonEntry& e : entries)
      if (e.key == std::string(var_name(var)) + "_knee") knee = number(e.key);
    if (!(knee > 0.0) || !std::isfinite(1.0 / knee))
      f.fail(std::string("root attribute creep_map: ") + var_name(var) + "_knee must be > 0");
    m.kinv[k] = 1.0 / knee;
    m.lo_k[k] = m.lo[k] / knee;
    m.hi_k[k] = m.hi[k] / knee;
    const Axis& a = d.axis[var];
    if (a.nodes()[0] != -1.0 || a.nodes()[a.size() - 1] != 1.0)
      f.fail(std::string("axis /axes/") + var_name(var) + " of a normalised creep part must run from -1 to 1");
  }
  if (!any) return;  // no creepage swept: nothing to map
  // The public axes (Table::axes, railtab_lookup_axis) of a normalised creepage: its physical
  // range, first and last value, in physical units (the nodes depend on the contact).
  for (AxisInfo& info : d.axes_info)
    for (int k = 0; k < 3; ++k)
      if (m.swept[k] && info.name == var_name(kVarXi + k)) {
        info.nodes = {m.lo[k], m.hi[k]};
        info.units = k == 2 ? "rad/m" : "1";
      }
  if (d.creep_block < 0) f.fail("root attribute creep_map but no creep or wear part");
  if (!d.has_part[kNormal]) f.fail("root attribute creep_map needs the normal part (its creep scales)");
  set_normal_grid(d, m);
  std::vector<hsize_t> expected(m.size, m.size + m.n_dims);
  expected.push_back(static_cast<hsize_t>(d.n_slots));
  static const char* const names[3] = {"creep_scale_xi", "creep_scale_eta", "creep_scale_phi"};
  static const char* const wheels[2] = {"/left/normal/", "/right/normal/"};
  for (int w = 0; w < 2; ++w) {
    m.scale[w].assign(m.nodes * static_cast<std::size_t>(d.n_slots) * 3, 0.0);
    for (int k = 0; k < 3; ++k) {
      const std::string ds = std::string(wheels[w]) + names[k];
      if (!f.exists(ds)) f.fail("missing dataset " + ds + " (root attribute creep_map needs it)");
      auto v = f.read_doubles(ds, expected, "the normal part's axes");
      check_checksum(f, d, ds, v.checksummed);
      for (std::size_t i = 0; i < v.values.size(); ++i) {
        const double x = v.values[i];
        if (!(std::isfinite(x) && x > 0.0 && std::isfinite(1.0 / x)))
          f.fail("dataset " + ds + " holds a scale that is not finite and > 0 at flat index " + std::to_string(i));
        const std::size_t node = i / static_cast<std::size_t>(d.n_slots), slot = i % static_cast<std::size_t>(d.n_slots);
        m.scale[w][(slot * m.nodes + node) * 3 + static_cast<std::size_t>(k)] = 1.0 / x;  // CreepMap::scale
      }
    }
  }
  m.active = true;
}

// Interleaves the parts that share one grid into a slot-major block (layout in table_data.hpp).
Block make_block(const std::vector<int>& parts, const std::vector<PartArrays>& arrays,
                 int n_slots) {
  Block b;
  const PartArrays& first = arrays[parts[0]];
  b.n_dims = static_cast<int>(first.vars.size());
  for (int k = 0; k < b.n_dims; ++k) b.var[k] = first.vars[k];
  b.n_parts = static_cast<int>(parts.size());
  b.first_output = arrays[parts[0]].output_of.front();
  for (int k = 0; k < b.n_parts; ++k) {
    b.part[k] = parts[k];
    for (int o : arrays[parts[k]].output_of) {
      if (o != b.first_output + b.n_values) b.first_output = -1;
      b.output_of[b.n_values++] = o;
    }
  }
  for (int k = 0; k < b.n_dims; ++k) b.size[k] = static_cast<int>(first.dims[k]);
  const std::size_t ns = static_cast<std::size_t>(n_slots);
  const std::size_t nv = static_cast<std::size_t>(b.n_values), np = static_cast<std::size_t>(b.n_parts);
  std::vector<double> values(ns * first.nodes * nv);
  std::vector<StatusBits> status(ns * first.nodes * np);
  for (std::size_t s = 0; s < ns; ++s) {
    for (std::size_t node = 0; node < first.nodes; ++node) {
      double* v = values.data() + (s * first.nodes + node) * nv;
      StatusBits* st = status.data() + (s * first.nodes + node) * np;
      for (int part : parts) {
        for (const auto& out : arrays[part].outputs) *v++ = out[node * ns + s];
        *st++ = arrays[part].status[node * ns + s];
      }
    }
  }
  prepare_query_layout(b, values, status, n_slots);  // block_layout.cpp: the layout the query path reads
  return b;
}

}  // namespace

namespace {

std::shared_ptr<TableData> load_checked(const std::string& path, const LoadOptions& options) {
  if (options.method != Method::kLinear && options.method != Method::kCubic &&
      options.method != Method::kMonotoneCubic)
    throw LoadError(path, "unknown interpolation method " +
                              std::to_string(static_cast<int>(options.method)));
  Hdf5ErrorsSilenced quiet;
  Hdf5File f(path);
  auto d = std::make_shared<TableData>();
  d->path = path;
  d->method = options.method;
  if (!f.has_attribute("/", "format_version"))
    f.fail("missing root attribute format_version (not a railtab table?)");
  read_integrity(f, *d, options);  // before any string is read: decides how strings are read
  // Checksummed table: every string attribute of the file, not only those read below, so that a
  // caller reading more of the file after a successful load (`railtab inspect`) meets no
  // variable-length string (refused) and no oversized one. Not for a legacy table: libhdf5
  // 1.10.8 itself crashes decoding some corrupt attribute messages that listing all of them
  // would touch (measured: 5 in 1,000 single-byte changes), while the lookup alone reads none.
  if (d->checksums_verified) f.check_all_string_attributes();
  const int major = read_version(f, *d);
  if (!options.accept_shard) refuse_shard(f);
  d->scene_name = f.string_attribute("/", "scene_name").value_or("");
  read_axes(f, *d, major);
  if (major == 1) read_fixed_axes(f, *d);  // format 2 stores them in /axes (read_axes)
  else check_fixed_variables(f, *d);
  for (const int var : kFileOrder) {
    if (d->tabulated[var]) d->tabulated_var[d->n_tabulated++] = var;
    // Roll following the equilibrium is checked as a variable fixed at 0 (not listed in
    // fixed_axes): the table holds no other roll, so a query that sets one is flagged
    // kOutOfRange (NaN/inf: kInvalidInput) instead of being answered at the equilibrium silently.
    // So is yaw in a table without it (before format 2.4, or a scene without yaw): every value
    // was computed at yaw 0.
    const bool implicit_zero = (var == kVarRoll && d->roll_equilibrium) || (var == kVarYaw && d->yaw_absent);
    if (d->fixed[var] || implicit_zero) d->fixed_var[d->n_fixed++] = var;
    // A fixed variable counts as "at its fixed value" within 1e-9 relative (absolute below
    // magnitude 1): round-off in the caller's state must not flag kOutOfRange.
    d->fixed_tolerance[var] = 1e-9 * std::max(1.0, std::abs(d->fixed_value[var]));
  }

  static const char* const wheels[2] = {"/left", "/right"};
  for (int p = 0; p < kNumParts; ++p) {
    const std::string left = std::string(wheels[0]) + "/" + kPartSpecs[p].name;
    const std::string right = std::string(wheels[1]) + "/" + kPartSpecs[p].name;
    const bool has_left = f.exists(left), has_right = f.exists(right);
    if (has_left != has_right)
      f.fail("part " + std::string(kPartSpecs[p].name) + " present for one wheel only (" +
             (has_left ? left : right) + " exists, " + (has_left ? right : left) + " does not)");
    d->has_part[p] = has_left;
    if (!has_left) d->absent_part[d->n_absent++] = p;
  }
  // Parts over the same axes share a block; the grouping is the same for both wheels.
  std::vector<std::vector<int>> groups;
  for (int p = 0; p < kNumParts; ++p) {
    if (!d->has_part[p]) continue;
    auto same_axes = [&](int q) {
      for (int var = 0; var < kNumVars; ++var)
        if (d->tabulated[var] && kPartSpecs[p].uses[var] != kPartSpecs[q].uses[var]) return false;
      return true;
    };
    auto g = std::find_if(groups.begin(), groups.end(),
                          [&](const std::vector<int>& group) { return same_axes(group[0]); });
    if (g == groups.end()) groups.push_back({p});
    else g->push_back(p);
  }
  if (groups.empty())
    f.fail("no part found: expected groups /left/<part> and /right/<part> with part one of "
           "geometry, normal, creep, wear");
  d->n_blocks = static_cast<int>(groups.size());
  for (int w = 0; w < 2; ++w) {
    std::vector<PartArrays> arrays(kNumParts);
    for (int p = 0; p < kNumParts; ++p)
      if (d->has_part[p])
        arrays[p] = read_part(f, *d, std::string(wheels[w]) + "/" + kPartSpecs[p].name,
                              kPartSpecs[p]);
    for (int b = 0; b < d->n_blocks; ++b) {
      // A record holds at most kMaxSlotValues values: when every part shares one block (nothing
      // but y and roll swept) the creep part's normal contact is left out (the normal part's,
      // identical without creepage, is served).
      std::size_t n = 0;
      for (int p : groups[b]) n += arrays[p].outputs.size();
      if (n > static_cast<std::size_t>(kMaxSlotValues) && d->has_part[kCreep]) {
        arrays[kCreep].outputs.resize(static_cast<std::size_t>(kPartSpecs[kCreep].n_out));
        arrays[kCreep].output_of.resize(static_cast<std::size_t>(kPartSpecs[kCreep].n_out));
      }
      d->block[w][b] = make_block(groups[b], arrays, d->n_slots);
      if (std::find(groups[b].begin(), groups[b].end(), static_cast<int>(kCreep)) != groups[b].end() ||
          std::find(groups[b].begin(), groups[b].end(), static_cast<int>(kWear)) != groups[b].end())
        d->creep_block = b;
    }
  }
  read_creep_map(f, *d);
  read_jumps(f, *d);  // format 2.1; absent: no one-sided cells (as before)
  read_creep_coefficients(f, *d);  // format 2.3; absent: has_creep_coefficients() false
  read_error_map(f, *d);  // format 2.3; absent: no error estimate
  mark_unbalanced_load(*d);  // low_confidence.hpp: the load-balance rule
  narrow_exact_blocks(*d);  // float records where every value is a float (format 2.2's creep, wear)
  // What the query does with each tabulated variable, fixed here so its loop has no branch on it.
  for (int k = 0; k < d->n_tabulated; ++k) {
    const int var = d->tabulated_var[k];
    if (d->creep_map.active && is_creepage(var)) d->clamped_var[d->n_clamped++] = var;
    else d->located_var[d->n_located++] = var;
  }
  prepare_fast_path(*d);  // fast_path.hpp: the fused query for the usual shape
  return d;
}

}  // namespace

std::shared_ptr<TableData> load_table_data(const std::string& path, const LoadOptions& options) {
  // Every extent is checked against the file before it is allocated, so running out of memory
  // here means the machine is short of it for a valid table: still a LoadError (one type to
  // catch, and nothing but LoadError leaves Table::load).
  try {
    return load_checked(path, options);
  } catch (const std::bad_alloc&) {
    throw LoadError(path, "out of memory while loading (Table::memory_bytes of a similar table "
                          "says how much it needs)");
  } catch (const std::length_error& e) {
    throw LoadError(path, std::string("a size is out of range: ") + e.what());
  }
}

}  // namespace railtab::lookup::detail
