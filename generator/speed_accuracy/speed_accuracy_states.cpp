// SPDX-License-Identifier: Apache-2.0
// The states of the speed-against-accuracy measurement: CONTACT's block C rows (reference values)
// or, without the reference file, the same states at the target creepages.
#include "speed_accuracy/speed_accuracy_states.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/check.hpp"

namespace railtab {
namespace {

struct CreepTarget {
  const char* name;
  double cksi, ceta, cphi;  // CONTACT's targets
};
constexpr CreepTarget kCreepSets[] = {{"a_none", 0, 0, 0},
                                      {"b_long0.001", 0.001, 0, 0},
                                      {"c_lat0.001", 0, 0.001, 0},
                                      {"d_spin0.052", 0, 0, 0.052},
                                      {"e_combined", 0.003, 0.002, 0.1}};

bool wanted(const std::vector<std::string>& sets, const std::string& s) {
  return sets.empty() || std::find(sets.begin(), sets.end(), s) != sets.end();
}
bool wanted(const std::vector<double>& dys, double dy) {
  return dys.empty() || std::any_of(dys.begin(), dys.end(), [dy](double d) { return std::abs(d - dy) < 1e-9; });
}

void classify(SaState& s) {
  s.y = -s.dy_mm * 1e-3;
  s.flange = s.dy_mm >= 6.5;  // CONTACT: flange contact from dy = 6.5 mm
  s.creep = s.xi != 0.0 || s.eta != 0.0 || s.phi != 0.0;
  if (s.creep_set == "a_none") s.creep = false;  // CONTACT's tiny residual creepages are not a case
}

}  // namespace

std::vector<SaState> read_contact_states(const std::filesystem::path& path, const SpeedAccuracyOptions& opt) {
  std::ifstream in(path);
  RAILTAB_CHECK(in.good(), "cannot read {}", path.string());
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::size_t> col;
  {
    std::stringstream ss(line);
    std::string name;
    for (std::size_t i = 0; std::getline(ss, name, ','); ++i) col[name] = i;
  }
  for (const char* need : {"dy_mm", "creep_set", "mu", "fz_prescribed_N", "cksi", "ceta", "cphi_rad_per_m",
                           "fx_N", "fs_N", "area_mm2", "pmax_MPa", "contact_angle_rad"}) {
    RAILTAB_CHECK(col.count(need) == 1, "{}: column '{}' missing", path.string(), need);
  }
  std::map<std::pair<double, std::string>, SaState> by_key;  // the file repeats the dy = -6 rows
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    auto num = [&](const char* name) { return std::stod(f.at(col.at(name))); };
    SaState s;
    s.dy_mm = num("dy_mm");
    s.creep_set = f.at(col.at("creep_set"));
    if (!wanted(opt.dy_mm, s.dy_mm) || !wanted(opt.creep_sets, s.creep_set)) continue;
    s.friction = num("mu");
    s.load = num("fz_prescribed_N");
    // Conventions (docs/conventions.md), right wheel: xi = -cksi, eta = +ceta, phi = +cphi,
    // fx = -fx_N, fy = +fs_N. The creepages CONTACT actually used, not the targets.
    s.xi = -num("cksi");
    s.eta = num("ceta");
    s.phi = num("cphi_rad_per_m");
    s.ref_fx = -num("fx_N");
    s.ref_fy = num("fs_N");
    s.ref_area = num("area_mm2") * 1e-6;
    s.ref_pmax = num("pmax_MPa") * 1e6;
    s.ref_angle = num("contact_angle_rad");
    s.ref_fn = num("fn_N");
    classify(s);
    s.normal_reliable = !(s.creep_set == "a_none" && std::abs(s.dy_mm - 7.0) < 1e-9);  // README outlier
    by_key[{s.dy_mm, s.creep_set}] = s;
  }
  std::vector<SaState> states;
  for (const auto& [key, s] : by_key) states.push_back(s);
  RAILTAB_CHECK(!states.empty(), "{}: no block C state matches the selection", path.string());
  return states;
}

std::vector<SaState> target_states(const SpeedAccuracyOptions& opt, const Scene& scene) {
  std::vector<SaState> states;
  for (int dy = -6; dy <= 10; ++dy) {
    if (!wanted(opt.dy_mm, dy)) continue;
    for (const CreepTarget& c : kCreepSets) {
      if (!wanted(opt.creep_sets, c.name)) continue;
      SaState s;
      s.dy_mm = dy;
      s.creep_set = c.name;
      s.friction = scene.tangential.friction;
      s.xi = -c.cksi;
      s.eta = c.ceta;
      s.phi = c.cphi;
      classify(s);
      states.push_back(s);
    }
  }
  RAILTAB_CHECK(!states.empty(), "speed-accuracy: no state matches the selection");
  return states;
}

}  // namespace railtab
