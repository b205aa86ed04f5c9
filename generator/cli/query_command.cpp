// SPDX-License-Identifier: Apache-2.0
// railtab query TABLE.h5 (--y Y[,Y...] | --states FILE) [--roll R] [--yaw A] [--load N] [--creepage XI,ETA,PHI]
//               [--wheel W] [--method M] [--derivatives] [--creep-coefficients] [--json]
// Interpolates a table with the runtime library (railtab::lookup, exactly what a simulation
// gets): every output of every slot at each state, with units and status text. Checks a table
// one ships against `railtab eval` (the direct models) at the same state. States are printed as
// they are read (from --y or a states file, stdin included): memory does not grow with their number.
// --derivatives adds each output's exact partial derivatives of the interpolant with respect to
// every tabulated axis; --creep-coefficients each slot's linear creep coefficients (format 2.3).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "cli/number_options.hpp"
#include "cli/query_states.hpp"
#include "core/check.hpp"
#include "core/status.hpp"
#include "railtab/lookup.hpp"
#include "scene/state_rules.hpp"

namespace railtab {
namespace {

namespace lk = railtab::lookup;

struct QueryOptions {
  std::string table;
  std::vector<double> y;          // one state per value [m]
  std::string states;             // states file ('-': stdin), instead of --y
  std::optional<double> roll;     // [rad]
  std::optional<double> yaw;      // [rad]
  bool derivatives = false;       // also the partial derivatives per tabulated axis
  bool creep_coefficients = false;  // also the linear creep coefficients per slot
  std::optional<double> load;     // [N]
  std::vector<double> creepage;   // xi, eta [1], phi [rad/m]; empty: 0, 0, 0
  std::string wheel = "both";     // left, right or both
  std::string method = "linear";  // interpolation method
  bool json = false;
  bool error_estimate = false;    // also the table's stored error map where each slot lands
};

// SI units of the outputs, in lookup::Output order (docs/table-format.md; the table file's
// `units` attributes hold the same, tests/python checks them against a generated table).
constexpr const char* kOutputUnits[lk::kNumOutputs] = {
    "rad", "m", "m", "m", "m", "1/m", "1/m", "N", "m", "m2", "Pa", "m", "m", "N", "N", "N m", "1", "m2/m"};
constexpr const char* kSlotNames[] = {"tread", "flange", "slot 2", "slot 3"};

lk::Method parse_method(const std::string& name) {
  if (name == "linear") return lk::Method::kLinear;
  if (name == "cubic") return lk::Method::kCubic;
  if (name == "monotone-cubic") return lk::Method::kMonotoneCubic;
  RAILTAB_CHECK(false, "--method must be linear, cubic or monotone-cubic, got '{}'", name);
  return lk::Method::kLinear;
}

bool is_axis(const lk::Table& table, const std::string& name) {
  for (const lk::AxisInfo& a : table.axes())
    if (a.name == name) return true;
  return false;
}

bool is_fixed(const lk::Table& table, const std::string& name) {
  for (const auto& [fixed, value] : table.fixed_axes())
    if (fixed == name) return true;
  return false;
}

// One variable of the state: given, else the table's fixed value (default_state), else an
// error when the table tabulates it (a query at an arbitrary value would mislead).
void set_variable(const lk::Table& table, const std::optional<double>& given, const char* name, double& value) {
  if (given) {
    value = *given;  // checked by its option's rule (number_options.hpp)
  } else {
    RAILTAB_CHECK(!is_axis(table, name), "{}: {} is an axis of this table: give --{}", table.path(), name, name);
  }
}

nlohmann::ordered_json contact_json(const lk::Table& table, const lk::Contact& c, int slot) {
  nlohmann::ordered_json j;
  j["slot"] = slot;
  j["slot_name"] = kSlotNames[slot];
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    const auto out = static_cast<lk::Output>(o);
    if (table.has_part(lk::output_part(out))) j[lk::output_name(out)] = c.value[o];
  }
  j["status"] = status::describe(c.status);
  j["status_bits"] = c.status;
  return j;
}

// {output: {axis: d output / d axis}} for the outputs the table holds and its tabulated axes.
nlohmann::ordered_json derivatives_json(const lk::Table& table, const double (*d)[lk::kNumVariables]) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    const auto out = static_cast<lk::Output>(o);
    if (!table.has_part(lk::output_part(out))) continue;
    nlohmann::ordered_json per_axis = nlohmann::ordered_json::object();
    for (const lk::AxisInfo& a : table.axes())
      for (int v = 0; v < lk::kNumVariables; ++v)
        if (a.name == lk::variable_name(v)) per_axis[a.name] = d[o][v];
    j[lk::output_name(out)] = per_axis;
  }
  return j;
}

// Units of the linear creep coefficients [force][creepage] (docs/conventions.md, "Linear creep
// coefficients").
constexpr const char* kForceNames[3] = {"fx", "fy", "mz"};
constexpr const char* kCreepageNames[3] = {"xi", "eta", "phi"};
constexpr const char* kCoefficientUnits[3][3] = {{"N", "N", "N m"}, {"N", "N", "N m"}, {"N m", "N m", "N m2"}};

// {fx: {xi: .., eta: .., phi: ..}, fy: {..}, mz: {..}} of one slot.
nlohmann::ordered_json coefficients_json(const double (&k)[3][3]) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (int f = 0; f < 3; ++f)
    for (int c = 0; c < 3; ++c) j[kForceNames[f]][kCreepageNames[c]] = k[f][c];
  return j;
}

// The stored error map's region (y band x slot) holding y (format 2.3; null before): RMS and max
// of each quantity and the sample count, per comparison.
nlohmann::ordered_json error_estimate_json(const lk::Table& table, double y, int slot) {
  lk::ErrorEstimate e;
  if (!table.error_estimate(y, slot, e)) return nullptr;
  static constexpr const char* kNames[lk::kErrorQuantities] = {"fx", "fy", "mz", "normal_force", "contact_angle"};
  auto stats = [](const lk::ErrorStats& s) {
    nlohmann::ordered_json j;
    j["samples"] = s.samples;
    for (int q = 0; q < lk::kErrorQuantities; ++q) {  // NaN (no sample) prints as null
      j[fmt::format("{}_rms", kNames[q])] = s.rms[q];
      j[fmt::format("{}_max", kNames[q])] = s.max[q];
    }
    return j;
  };
  nlohmann::ordered_json j;
  j["y_band"] = {e.y_band_start, e.y_band_end};
  j["units"] = {{"fx", "% of mu N"}, {"fy", "% of mu N"}, {"mz", "% of mu N c"}, {"normal_force", "%"},
                {"contact_angle", "rad"}};
  j["table_vs_model"] = stats(e.table_vs_model);
  if (e.exact_measured) j["model_vs_exact"] = stats(e.model_vs_exact);
  else j["model_vs_exact"] = e.same_model ? nlohmann::ordered_json("same model") : nlohmann::ordered_json(nullptr);
  return j;
}

// Text: the header once, then one block per query.
void print_text_header(const nlohmann::ordered_json& head) {
  std::cout << fmt::format("table {} (scene {}, format {}), {} interpolation\n", head["table"].get<std::string>(),
                           head["scene_name"].get<std::string>(), head["format_version"].get<std::string>(),
                           head["method"].get<std::string>());
}

void print_text_query(const nlohmann::ordered_json& units, const nlohmann::ordered_json& q) {
  const auto& s = q["state"];
  std::string roll = s["roll"].is_null() ? "the table's equilibrium roll"
                                         : fmt::format("{:g} rad", s["roll"].get<double>());
  if (s.contains("yaw")) roll += fmt::format(", yaw = {:g} rad", s["yaw"].get<double>());
  std::cout << fmt::format("\n{} wheel: y = {:g} m, roll = {}, load = {:g} N, xi = {:g}, eta = {:g}, "
                           "phi = {:g} rad/m; query status {}\n",
                           q["wheel"].get<std::string>(), s["y"].get<double>(), roll, s["load"].get<double>(),
                           s["xi"].get<double>(), s["eta"].get<double>(), s["phi"].get<double>(),
                           q["query_status"].get<std::string>());
  const auto& contacts = q["contacts"];
  std::cout << fmt::format("  {:<16} {:>8}", "output", "units");
  for (const auto& c : contacts) std::cout << fmt::format(" {:>14}", c["slot_name"].get<std::string>());
  std::cout << "\n";
  for (const auto& [name, unit] : units.items()) {
    std::cout << fmt::format("  {:<16} {:>8}", name, unit.get<std::string>());
    for (const auto& c : contacts) std::cout << fmt::format(" {:>14.6g}", c[name].get<double>());
    std::cout << "\n";
  }
  std::cout << fmt::format("  {:<16} {:>8}", "status", "");
  for (const auto& c : contacts) std::cout << fmt::format(" {:>14}", c["status"].get<std::string>());
  std::cout << "\n";
  if (!contacts.empty() && contacts[0].contains("error_estimate")) {
    std::cout << "  stored error map, max in the region (fx, fy % of mu N; normal force %):\n";
    for (const char* comparison : {"table_vs_model", "model_vs_exact"}) {
      std::cout << fmt::format("  {:<25}", comparison);
      for (const auto& c : contacts) {
        const auto& e = c["error_estimate"];
        const auto* region = e.is_object() && e[comparison].is_object() ? &e[comparison] : nullptr;
        auto num = [&](const char* k) {
          const bool known = (*region)[k].is_number() && !std::isnan((*region)[k].get<double>());
          return known ? fmt::format("{:.2g}", (*region)[k].get<double>()) : std::string("-");
        };
        std::string cell = !e.is_object()                  ? "none"
                           : e[comparison].is_string()     ? e[comparison].get<std::string>()
                           : !region                       ? "-"
                                                           : fmt::format("{}/{}/{}", num("fx_max"), num("fy_max"),
                                                                         num("normal_force_max"));
        std::cout << fmt::format(" {:>14}", cell);
      }
      std::cout << "\n";
    }
  }
  if (!contacts.empty() && contacts[0].contains("derivatives")) {
    std::cout << "  partial derivatives (output units per axis unit):\n";
    for (const auto& [name, unit] : units.items())
      for (const auto& [axis, value] : contacts[0]["derivatives"][name].items()) {
        std::cout << fmt::format("  d {:<12} / d {:<4}", name, axis);
        for (const auto& c : contacts) std::cout << fmt::format(" {:>14.6g}", c["derivatives"][name][axis].get<double>());
        std::cout << "\n";
      }
  }
  if (!contacts.empty() && contacts[0].contains("creep_coefficients")) {
    std::cout << "  linear creep coefficients (zero creepage, full adhesion):\n";
    for (int f = 0; f < 3; ++f)
      for (int c = 0; c < 3; ++c) {
        std::cout << fmt::format("  d {:<12} / d {:<4}{:>6}", kForceNames[f], kCreepageNames[c], kCoefficientUnits[f][c]);
        for (const auto& x : contacts)
          std::cout << fmt::format(" {:>14.6g}", x["creep_coefficients"][kForceNames[f]][kCreepageNames[c]].get<double>());
        std::cout << "\n";
      }
    std::cout << fmt::format("  {:<25}", "coefficient status");
    for (const auto& x : contacts) std::cout << fmt::format(" {:>14}", x["creep_coefficient_status"].get<std::string>());
    std::cout << "\n";
  }
}

// JSON: the text nlohmann's dump(2) gives for {header..., "queries": [q, q, ...]}, written one
// query at a time.
class JsonQueryWriter {
 public:
  explicit JsonQueryWriter(const nlohmann::ordered_json& head) {
    std::string text = head.dump(2);  // "{\n  ...\n}"
    text.resize(text.size() - 2);     // without "\n}"
    std::cout << text << ",\n  \"queries\": [";
  }
  void add(const nlohmann::ordered_json& q) {
    std::string text = first_ ? "\n    " : ",\n    ";
    for (const char c : q.dump(2)) {  // one level deeper: 4 more spaces after every line end
      text += c;
      if (c == '\n') text += "    ";
    }
    std::cout << text;
    first_ = false;
  }
  void finish() { std::cout << (first_ ? "]\n}\n" : "\n  ]\n}\n"); }

 private:
  bool first_ = true;
};

void run_query(const QueryOptions& opt) {
  RAILTAB_CHECK(!opt.y.empty() || !opt.states.empty(), "give the states: --y Y[,Y...] or --states FILE");
  RAILTAB_CHECK(opt.wheel == "left" || opt.wheel == "right" || opt.wheel == "both",
                "--wheel must be left, right or both, got '{}'", opt.wheel);
  const lk::Method method = parse_method(opt.method);
  lk::Table table = [&] {
    try {
      return lk::Table::load(opt.table, {method});
    } catch (const lk::LoadError& e) {
      throw Error(e.what());
    }
  }();
  RAILTAB_CHECK(!opt.derivatives || method != lk::Method::kMonotoneCubic,
                "--derivatives needs --method linear or cubic: the monotone cubic's limited slopes are not "
                "differentiated");
  RAILTAB_CHECK(!opt.creep_coefficients || table.has_creep_coefficients(),
                "--creep-coefficients: {}: this table holds no linear creep coefficients (format {}; they are "
                "stored since format 2.3): regenerate it with railtab generate",
                table.path(), table.format_version());
  // The states file is opened before anything is printed: a missing one prints nothing.
  std::unique_ptr<StateReader> reader;
  if (!opt.states.empty()) reader = std::make_unique<StateReader>(opt.states);
  lk::State base = table.default_state();
  // A table whose roll follows the equilibrium holds no other roll: --roll would be answered at
  // the equilibrium anyway (the lookup flags it out_of_range), so it is refused outright.
  RAILTAB_CHECK(!opt.roll || is_axis(table, "roll") || is_fixed(table, "roll"),
                "--roll: {}: the table's roll follows the kinematic equilibrium at each y (roll_mode = "
                "equilibrium), so roll is not an input; leave --roll out",
                table.path());
  set_variable(table, opt.roll, "roll", base.roll);
  // A table without yaw was computed at yaw 0: another yaw would be answered at 0 (the lookup flags
  // it out_of_range), so it is refused outright.
  const bool has_yaw = is_axis(table, "yaw") || is_fixed(table, "yaw");
  RAILTAB_CHECK(!opt.yaw || *opt.yaw == 0.0 || has_yaw,
                "--yaw: {}: the table has no yaw (computed at yaw 0: no yaw axis or fixed yaw, format {}); a yaw "
                "of {:g} rad would be answered at yaw 0: query a table of a scene with [grid] yaw",
                table.path(), table.format_version(), opt.yaw.value_or(0.0));
  if (!reader || !reader->has("yaw")) set_variable(table, opt.yaw, "yaw", base.yaw);
  else if (opt.yaw) base.yaw = *opt.yaw;
  if (!reader || !reader->has("load")) set_variable(table, opt.load, "load", base.load);
  else if (opt.load) base.load = *opt.load;
  if (!opt.creepage.empty()) {
    base.xi = opt.creepage[0];
    base.eta = opt.creepage[1];
    base.phi = opt.creepage[2];
  }
  nlohmann::ordered_json head;
  head["table"] = table.path();
  head["scene_name"] = table.scene_name();
  head["format_version"] = table.format_version();
  head["method"] = opt.method;
  head["units"] = nlohmann::ordered_json::object();
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    const auto output = static_cast<lk::Output>(o);
    if (table.has_part(lk::output_part(output))) head["units"][lk::output_name(output)] = kOutputUnits[o];
  }
  if (opt.creep_coefficients) {
    nlohmann::ordered_json& u = head["creep_coefficient_units"];
    for (int f = 0; f < 3; ++f)
      for (int c = 0; c < 3; ++c) u[kForceNames[f]][kCreepageNames[c]] = kCoefficientUnits[f][c];
  }
  // Roll that is neither tabulated nor fixed follows the table's equilibrium roll: not an input.
  const bool roll_is_input = is_axis(table, "roll") || is_fixed(table, "roll");
  if (reader && reader->has("roll")) {
    RAILTAB_CHECK(roll_is_input, "{}: column roll: this table follows its equilibrium roll; a roll would be ignored",
                  opt.states);
  }
  // A yaw column on a table without yaw: each non-zero yaw is flagged out_of_range by the lookup.
  std::optional<JsonQueryWriter> json;
  if (opt.json) json.emplace(head);
  else print_text_header(head);
  const auto answer = [&](const lk::State& s) {
    for (int w = 0; w < 2; ++w) {
      if ((opt.wheel == "left" && w == 1) || (opt.wheel == "right" && w == 0)) continue;
      lk::Result r;
      auto d = std::make_unique<lk::Derivatives>();
      if (opt.derivatives) table.query_derivatives(static_cast<lk::Wheel>(w), s, r, *d);
      else table.query(static_cast<lk::Wheel>(w), s, r);
      lk::CreepCoefficients k;
      if (opt.creep_coefficients) table.query_creep_coefficients(static_cast<lk::Wheel>(w), s, k);
      nlohmann::ordered_json q;
      q["wheel"] = w == 0 ? "left" : "right";
      q["state"] = {{"y", s.y}, {"roll", s.roll}, {"load", s.load}, {"xi", s.xi}, {"eta", s.eta}, {"phi", s.phi}};
      if (!roll_is_input) q["state"]["roll"] = nullptr;
      if (has_yaw || s.yaw != 0.0) q["state"]["yaw"] = s.yaw;  // a yaw-free table's answers as before
      q["query_status"] = status::describe(r.status);
      q["contacts"] = nlohmann::ordered_json::array();
      for (int slot = 0; slot < r.n_slots; ++slot) {
        q["contacts"].push_back(contact_json(table, r.contact[slot], slot));
        if (opt.derivatives) q["contacts"].back()["derivatives"] = derivatives_json(table, d->d[slot]);
        if (opt.creep_coefficients) {
          q["contacts"].back()["creep_coefficients"] = coefficients_json(k.k[slot]);
          q["contacts"].back()["creep_coefficient_status"] = status::describe(k.status[slot]);
        }
        if (opt.error_estimate) q["contacts"].back()["error_estimate"] = error_estimate_json(table, s.y, slot);
      }
      if (json) json->add(q);
      else print_text_query(head["units"], q);
    }
  };
  if (reader) {
    lk::State s = base;
    bool any = false;
    while (reader->next(s)) {
      answer(s);
      s = base;
      any = true;
    }
    RAILTAB_CHECK(any, "{}: no states (a header line, then one state per line)", opt.states);
  } else {
    for (double y : opt.y) {
      lk::State s = base;
      s.y = y;
      answer(s);
    }
  }
  if (json) json->finish();
  std::cout.flush();
}

}  // namespace

void add_query_command(CLI::App& app) {
  auto opt = std::make_shared<QueryOptions>();
  CLI::App* cmd = app.add_subcommand(
      "query", "Interpolate a table with the runtime lookup at given states (what a simulation gets)");
  cmd->add_option("table", opt->table, "Table file (HDF5)")->required();
  CLI::Option* y = add_number_list_option(
      cmd, "--y", opt->y, kLateralShiftRule,
      "Wheelset lateral displacement(s) [m], + to the left; comma-separated for several");
  CLI::Option* states =
      cmd->add_option("--states", opt->states,
                      "States file ('-': stdin), read and answered one line at a time: a header naming the "
                      "columns (y and any of roll, load, xi, eta, phi, yaw), then one state per line; columns not "
                      "given come from --roll, --load, --creepage");
  y->excludes(states);
  cmd->add_flag("--derivatives", opt->derivatives,
               "Also each output's partial derivatives with respect to every tabulated axis (exact for the "
               "interpolant, SI: output units per axis unit; linear and cubic methods)");
  cmd->add_flag("--creep-coefficients", opt->creep_coefficients,
               "Also each slot's linear creep coefficients: d fx, fy, mz / d xi, eta, phi at zero creepage in "
               "full adhesion, interpolated over y, roll and load (tables of format 2.3)");
  add_number_option(cmd, "--roll", opt->roll, kRollRule, "Wheelset roll [rad] (default: the table's fixed value)");
  add_number_option(cmd, "--yaw", opt->yaw, kYawRule,
                    "Wheelset yaw (angle of attack) [rad], + turns the forward axis to the left (default: the table's "
                    "fixed value, 0 for a table without yaw)");
  add_number_option(cmd, "--load", opt->load, kWheelLoadRule,
                    "Vertical wheel load [N] (default: the table's fixed value)");
  static constexpr std::array<NumberField, 3> kCreepage{
      {{"xi", kCreepageRule}, {"eta", kCreepageRule}, {"phi", kSpinCreepageRule}}};
  add_number_fields_option(cmd, "--creepage", opt->creepage, kCreepage,
                           "Creepages XI,ETA,PHI [1, 1, rad/m] (default 0,0,0)");
  // A value outside the list is a usage error (exit 2, README), like an unknown option.
  cmd->add_option("--wheel", opt->wheel, "left, right or both")
      ->check(CLI::IsMember({"left", "right", "both"}))
      ->capture_default_str();
  cmd->add_option("--method", opt->method, "Interpolation: linear, cubic or monotone-cubic")
      ->check(CLI::IsMember({"linear", "cubic", "monotone-cubic"}))
      ->capture_default_str();
  cmd->add_flag("--json", opt->json, "Print JSON (stable keys, SI units) instead of text");
  cmd->add_flag("--error-estimate", opt->error_estimate,
                "Also the table's stored error map (format 2.3) in the region (y band x slot) of each contact: "
                "the table against its model and the model against the exact one, RMS and max");
  add_quiet_flag(cmd);  // query prints results only; accepted for uniformity
  cmd->callback([opt] {
    if (opt->y.empty() && opt->states.empty()) throw CLI::RequiredError("--y or --states");  // exit 2
    run_query(*opt);
  });
}

}  // namespace railtab
