// SPDX-License-Identifier: Apache-2.0
// railtab query TABLE.h5 --y Y[,Y...] [--roll R] [--load N] [--creepage XI,ETA,PHI] [--wheel W]
//               [--method M] [--derivatives] [--json]
// Interpolates a table with the runtime library (railtab::lookup, exactly what a simulation
// gets): every output of every slot at each state, with units and status text. Checks a table
// one ships against `railtab eval` (the direct models) at the same state. --derivatives adds each
// output's exact partial derivatives of the interpolant with respect to every tabulated axis.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_common.hpp"
#include "cli/commands.hpp"
#include "core/check.hpp"
#include "core/status.hpp"
#include "railtab/lookup.hpp"

namespace railtab {
namespace {

namespace lk = railtab::lookup;

struct QueryOptions {
  std::string table;
  std::vector<double> y;          // one state per value [m]
  std::optional<double> roll;     // [rad]
  std::optional<double> load;     // [N]
  std::vector<double> creepage;   // xi, eta [1], phi [rad/m]; empty: 0, 0, 0
  std::string wheel = "both";     // left, right or both
  std::string method = "linear";  // interpolation method
  bool derivatives = false;       // also the partial derivatives per tabulated axis
  bool json = false;
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
    RAILTAB_CHECK(std::isfinite(*given), "--{} must be finite, got {}", name, *given);
    value = *given;
  } else {
    RAILTAB_CHECK(!is_axis(table, name), "{}: {} is an axis of this table: give --{}", table.path(), name, name);
  }
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

void print_text(const nlohmann::ordered_json& out) {
  std::cout << fmt::format("table {} (scene {}, format {}), {} interpolation\n", out["table"].get<std::string>(),
                           out["scene_name"].get<std::string>(), out["format_version"].get<std::string>(),
                           out["method"].get<std::string>());
  const auto& units = out["units"];
  for (const auto& q : out["queries"]) {
    const auto& s = q["state"];
    const std::string roll = s["roll"].is_null() ? "the table's equilibrium roll"
                                                 : fmt::format("{:g} rad", s["roll"].get<double>());
    std::cout << fmt::format("\n{} wheel: y = {:g} m, roll = {}, load = {:g} N, xi = {:g}, eta = {:g}, "
                             "phi = {:g} rad/m; query status {}\n",
                             q["wheel"].get<std::string>(), s["y"].get<double>(), roll,
                             s["load"].get<double>(), s["xi"].get<double>(), s["eta"].get<double>(),
                             s["phi"].get<double>(), q["query_status"].get<std::string>());
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
    if (!contacts.empty() && contacts[0].contains("derivatives")) {
      std::cout << "  partial derivatives (output units per axis unit):\n";
      for (const auto& [name, unit] : units.items())
        for (const auto& [axis, value] : contacts[0]["derivatives"][name].items()) {
          std::cout << fmt::format("  d {:<12} / d {:<4}", name, axis);
          for (const auto& c : contacts) std::cout << fmt::format(" {:>14.6g}", c["derivatives"][name][axis].get<double>());
          std::cout << "\n";
        }
    }
  }
}

void run_query(const QueryOptions& opt) {
  RAILTAB_CHECK(!opt.y.empty(), "--y: give at least one lateral displacement [m]");
  RAILTAB_CHECK(opt.creepage.empty() || opt.creepage.size() == 3,
                "--creepage takes XI,ETA,PHI (three numbers), got {} value(s)", opt.creepage.size());
  RAILTAB_CHECK(opt.wheel == "left" || opt.wheel == "right" || opt.wheel == "both",
                "--wheel must be left, right or both, got '{}'", opt.wheel);
  const lk::Method method = parse_method(opt.method);
  RAILTAB_CHECK(!opt.derivatives || method != lk::Method::kMonotoneCubic,
                "--derivatives needs --method linear or cubic: the monotone cubic's limited slopes are not "
                "differentiated");
  lk::Table table = [&] {
    try {
      return lk::Table::load(opt.table, {method});
    } catch (const lk::LoadError& e) {
      throw Error(e.what());
    }
  }();
  lk::State base = table.default_state();
  // A table whose roll follows the equilibrium holds no other roll: --roll would be answered at
  // the equilibrium anyway (the lookup flags it out_of_range), so it is refused outright.
  RAILTAB_CHECK(!opt.roll || is_axis(table, "roll") || is_fixed(table, "roll"),
                "--roll: {}: the table's roll follows the kinematic equilibrium at each y (roll_mode = "
                "equilibrium), so roll is not an input; leave --roll out",
                table.path());
  set_variable(table, opt.roll, "roll", base.roll);
  set_variable(table, opt.load, "load", base.load);
  if (!opt.creepage.empty()) {
    for (double c : opt.creepage) RAILTAB_CHECK(std::isfinite(c), "--creepage values must be finite, got {}", c);
    base.xi = opt.creepage[0];
    base.eta = opt.creepage[1];
    base.phi = opt.creepage[2];
  }
  nlohmann::ordered_json out;
  out["table"] = table.path();
  out["scene_name"] = table.scene_name();
  out["format_version"] = table.format_version();
  out["method"] = opt.method;
  out["units"] = nlohmann::ordered_json::object();
  for (int o = 0; o < lk::kNumOutputs; ++o) {
    const auto output = static_cast<lk::Output>(o);
    if (table.has_part(lk::output_part(output))) out["units"][lk::output_name(output)] = kOutputUnits[o];
  }
  out["queries"] = nlohmann::ordered_json::array();
  for (double y : opt.y) {
    RAILTAB_CHECK(std::isfinite(y), "--y values must be finite, got {}", y);
    for (int w = 0; w < 2; ++w) {
      if ((opt.wheel == "left" && w == 1) || (opt.wheel == "right" && w == 0)) continue;
      lk::State s = base;
      s.y = y;
      lk::Result r;
      auto d = std::make_unique<lk::Derivatives>();
      if (opt.derivatives) table.query_derivatives(static_cast<lk::Wheel>(w), s, r, *d);
      else table.query(static_cast<lk::Wheel>(w), s, r);
      nlohmann::ordered_json q;
      q["wheel"] = w == 0 ? "left" : "right";
      q["state"] = {{"y", s.y}, {"roll", s.roll}, {"load", s.load}, {"xi", s.xi}, {"eta", s.eta}, {"phi", s.phi}};
      // Roll that is neither tabulated nor fixed follows the table's equilibrium roll: not an input.
      if (!is_axis(table, "roll") && !is_fixed(table, "roll")) q["state"]["roll"] = nullptr;
      q["query_status"] = status::describe(r.status);
      q["contacts"] = nlohmann::ordered_json::array();
      for (int slot = 0; slot < r.n_slots; ++slot) {
        q["contacts"].push_back(contact_json(table, r.contact[slot], slot));
        if (opt.derivatives) q["contacts"].back()["derivatives"] = derivatives_json(table, d->d[slot]);
      }
      out["queries"].push_back(q);
    }
  }
  if (opt.json) {
    std::cout << out.dump(2) << "\n";
  } else {
    print_text(out);
  }
}

}  // namespace

void add_query_command(CLI::App& app) {
  auto opt = std::make_shared<QueryOptions>();
  CLI::App* cmd = app.add_subcommand(
      "query", "Interpolate a table with the runtime lookup at given states (what a simulation gets)");
  cmd->add_option("table", opt->table, "Table file (HDF5)")->required();
  cmd->add_option("--y", opt->y, "Wheelset lateral displacement(s) [m], + to the left; comma-separated for several")
      ->delimiter(',')
      ->required();
  cmd->add_option("--roll", opt->roll, "Wheelset roll [rad] (default: the table's fixed value)");
  cmd->add_option("--load", opt->load, "Vertical wheel load [N] (default: the table's fixed value)");
  cmd->add_option("--creepage", opt->creepage, "Creepages XI,ETA,PHI [1, 1, rad/m] (default 0,0,0)")
      ->delimiter(',')
      ->expected(3);
  // A value outside the list is a usage error (exit 2, README), like an unknown option.
  cmd->add_option("--wheel", opt->wheel, "left, right or both")
      ->check(CLI::IsMember({"left", "right", "both"}))
      ->capture_default_str();
  cmd->add_option("--method", opt->method, "Interpolation: linear, cubic or monotone-cubic")
      ->check(CLI::IsMember({"linear", "cubic", "monotone-cubic"}))
      ->capture_default_str();
  cmd->add_flag("--derivatives", opt->derivatives,
               "Also each output's partial derivatives with respect to every tabulated axis (exact for the "
               "interpolant, SI: output units per axis unit; linear and cubic methods)");
  cmd->add_flag("--json", opt->json, "Print JSON (stable keys, SI units) instead of text");
  add_quiet_flag(cmd);  // query prints results only; accepted for uniformity
  cmd->callback([opt] { run_query(*opt); });
}

}  // namespace railtab
