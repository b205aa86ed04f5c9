// SPDX-License-Identifier: Apache-2.0
// The contact kernel's cells: its outputs per part (names, units, how each is read from a result),
// storing one cell (non-finite -> failed), the kernel's data and the creepage of a grid node.
// Shared by contact_kernel.cpp (the columns) and creep_loops.cpp (the creep and wear loops); not a
// public header of the sweep.
#pragma once

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "geometry/contact_geometry.hpp"
#include "halfspace/wheel_rail.hpp"
#include "normal/normal_model.hpp"
#include "scene/scene.hpp"
#include "kernel/contact_kernel.hpp"
#include "kernel/creep_map.hpp"
#include "kernel/finite_status.hpp"
#include "engine/sweep.hpp"
#include "tangential/coupled_load.hpp"
#include "tangential/fastsim_contact.hpp"
#include "wear/archard.hpp"

namespace railtab::kernel {

// One float64 output of a part: dataset name, units, description, and how to get it from the
// part's per-contact result.
template <class Result>
struct Output {
  const char* name;
  const char* units;
  const char* description;
  double (*get)(const Result&);
};

// Geometry part, per contact point (axes y, roll, slot).
inline const Output<ContactPoint> kGeometryOutputs[] = {
    {"contact_angle", "rad", "contact angle, track frame, ISO sign (+ towards the flange for the left wheel)",
     [](const ContactPoint& p) { return p.contact_angle; }},
    {"rolling_radius", "m", "wheel rolling radius at the contact point",
     [](const ContactPoint& p) { return p.rolling_radius; }},
    {"wheel_y", "m", "contact position in the wheel profile frame (u)", [](const ContactPoint& p) { return p.wheel_u; }},
    {"rail_y", "m", "contact position in the rail profile frame (u)", [](const ContactPoint& p) { return p.rail_u; }},
    {"separation", "m", "vertical gap still open at rigid contact (0 = touching)",
     [](const ContactPoint& p) { return p.separation; }},
    {"curvature_a", "1/m", "relative curvature A, rolling direction", [](const ContactPoint& p) { return p.curvature_a; }},
    {"curvature_b", "1/m", "relative curvature B, lateral direction", [](const ContactPoint& p) { return p.curvature_b; }},
};

// Normal part, per contact patch (axes y, roll, load, slot).
inline const Output<ContactPatch> kNormalOutputs[] = {
    {"normal_force", "N", "normal force along the contact normal", [](const ContactPatch& c) { return c.normal_force; }},
    {"approach", "m", "normal approach at the patch reference point", [](const ContactPatch& c) { return c.penetration; }},
    {"area", "m2", "contact area", [](const ContactPatch& c) { return c.area; }},
    {"max_pressure", "Pa", "maximum contact pressure", [](const ContactPatch& c) { return c.max_pressure; }},
    {"a", "m", "rolling semi-axis (elliptic models; 0 for non-elliptic patches)",
     [](const ContactPatch& c) { return c.semi_axis_a; }},
    {"b", "m", "lateral semi-axis (elliptic models; 0 for non-elliptic patches)",
     [](const ContactPatch& c) { return c.semi_axis_b; }},
};

// Normal part, format 2.1 with normalised creep coordinates: the saturation scales of the slot's
// creepage-free contact (kernel/creep_map.hpp), which map the creep part's coordinates to
// creepages.
inline const OutputInfo kCreepScaleOutputs[] = {
    {"creep_scale_xi", "1", "longitudinal creepage scale s_xi = 3 mu N / (G c^2 C11) of the creep part's coordinate"},
    {"creep_scale_eta", "1", "lateral creepage scale s_eta = 3 mu N / (G c^2 C22) of the creep part's coordinate"},
    {"creep_scale_phi", "rad/m", "spin creepage scale s_phi = mu N / (G c^3 C23) of the creep part's coordinate"},
};

// Normal part, every table since format 2.3: the slot's linear creep coefficients, the slopes of
// its creep forces on the wheel against the creepages at zero creepage in full adhesion
// (tangential/linear_creep.hpp; docs/conventions.md, "Linear creep coefficients"), summed over the
// slot's loaded patches (mz each about its own patch's reference, as the creep part's). Order:
// force-major, [fx, fy, mz] x [xi, eta, phi], as LinearCreep::slope.
inline const OutputInfo kCreepCoefficientOutputs[] = {
    {"creep_coefficient_fx_xi", "N", "d fx / d xi at zero creepage, full adhesion (-G c^2 C11 on an ellipse)"},
    {"creep_coefficient_fx_eta", "N", "d fx / d eta at zero creepage, full adhesion"},
    {"creep_coefficient_fx_phi", "N m", "d fx / d phi at zero creepage, full adhesion [N per rad/m]"},
    {"creep_coefficient_fy_xi", "N", "d fy / d xi at zero creepage, full adhesion"},
    {"creep_coefficient_fy_eta", "N", "d fy / d eta at zero creepage, full adhesion (-G c^2 C22 on an ellipse)"},
    {"creep_coefficient_fy_phi", "N m", "d fy / d phi at zero creepage, full adhesion [N per rad/m] (-G c^3 C23 on an ellipse)"},
    {"creep_coefficient_mz_xi", "N m", "d mz / d xi at zero creepage, full adhesion"},
    {"creep_coefficient_mz_eta", "N m", "d mz / d eta at zero creepage, full adhesion (+G c^3 C23 on an ellipse)"},
    {"creep_coefficient_mz_phi", "N m2", "d mz / d phi at zero creepage, full adhesion [N m per rad/m]"},
};

// Creep part, per loaded patch and creepage (axes y, roll, load, xi, eta, phi, slot).
inline const Output<FastsimResult> kCreepOutputs[] = {
    {"fx", "N", "longitudinal creep force on the wheel (contact frame x)", [](const FastsimResult& r) { return r.fx; }},
    {"fy", "N", "lateral creep force on the wheel (contact frame s)", [](const FastsimResult& r) { return r.fy; }},
    {"mz", "N m", "spin moment on the wheel about the contact normal", [](const FastsimResult& r) { return r.mz; }},
    {"slip_fraction", "1", "slipping share of the contact area", [](const FastsimResult& r) { return r.slip_fraction; }},
};

// Normal contact of a creep point (creep part, format 1.2): with the load coupling the
// normal contact depends on the creepage, because the creep forces carry part of the vertical load.
inline const Output<ContactPatch> kCreepNormalOutputs[] = {
    {"normal_force", "N", "normal force along the contact normal at this creepage (load carried by normal and creep forces)",
     [](const ContactPatch& c) { return c.normal_force; }},
    {"approach", "m", "normal approach at the patch reference point at this creepage", [](const ContactPatch& c) { return c.penetration; }},
    {"area", "m2", "contact area at this creepage", [](const ContactPatch& c) { return c.area; }},
    {"max_pressure", "Pa", "maximum contact pressure at this creepage", [](const ContactPatch& c) { return c.max_pressure; }},
};

// Wear part, same grid as creep.
inline const Output<WearResult> kWearOutputs[] = {
    {"wear_rate", "m2/m", "worn wheel-profile cross-section per rolled distance (Archard, KTH map)",
     [](const WearResult& r) { return r.wear_rate; }},
};

template <class Result, std::size_t N>
PartSpec part_spec(const char* name, std::vector<std::string> inner_axes, const Output<Result> (&outputs)[N]) {
  PartSpec spec{name, std::move(inner_axes), {}};
  for (const Output<Result>& o : outputs) spec.outputs.push_back({o.name, o.units, o.description});
  return spec;
}

// The creep part: creep forces, then (with the load coupling) the normal contact at the creepage.
template <std::size_t N, std::size_t M>
PartSpec creep_part_spec(const Output<FastsimResult> (&creep)[N], const Output<ContactPatch> (&normal)[M],
                         bool coupled) {
  PartSpec spec = part_spec("creep", {"load", "xi", "eta", "phi"}, creep);
  if (coupled)
    for (const Output<ContactPatch>& o : normal) spec.outputs.push_back({o.name, o.units, o.description});
  return spec;
}

// One cell's outputs, written from output index `first` of the part. A NaN or inf in any of them
// writes zeros instead and a failure message naming the output, and returns false: the caller
// then marks the cell failed (non_finite_status), so a non-finite number is never `converged`
// (and the lookup refuses non-finite tables). `where` describes the cell (called only then).
template <class Result, std::size_t N, class Where>
bool store_values(const Output<Result> (&outputs)[N], const Result& result, ColumnOutput& out, std::size_t wheel,
                  std::size_t part, std::size_t cell, Where where, std::size_t first = 0) {
  double values[N];
  bool finite = true;
  for (std::size_t o = 0; o < N; ++o) {
    values[o] = outputs[o].get(result);
    finite = finite && std::isfinite(values[o]);
  }
  for (std::size_t o = 0; o < N; ++o) out.values(wheel, part, first + o)[cell] = finite ? values[o] : 0.0;
  if (!finite) {
    for (std::size_t o = 0; o < N; ++o) {
      if (!std::isfinite(values[o])) {
        out.failure(fmt::format("{}: {} = {} (not finite; stored as 0, status failed)", where(), outputs[o].name,
                                values[o]));
        break;
      }
    }
  }
  return finite;
}

// One cell's outputs and status (failed where an output is not finite).
template <class Result, std::size_t N, class Where>
void store(const Output<Result> (&outputs)[N], const Result& result, StatusBits bits, ColumnOutput& out,
           std::size_t wheel, std::size_t part, std::size_t cell, Where where) {
  const bool finite = store_values(outputs, result, out, wheel, part, cell, where);
  out.status(wheel, part)[cell] = finite ? bits : non_finite_status(bits);
}

inline constexpr std::size_t kGeometryPart = 0;
inline constexpr std::size_t kNormalPart = 1;
inline constexpr std::size_t kCreepPart = 2;
inline constexpr std::size_t kWearPart = 3;

// A point where the core threw: no values (zeros), and kFailed instead of kConverged.
inline StatusBits failure_status(const ColumnState& state) {
  bool bad_input = !std::isfinite(state.y) || !std::isfinite(state.roll);
  return status::kFailed | (bad_input ? status::kInvalidInput : 0u);
}

struct KernelData {
  ContactGeometrySolver solver;
  SceneGrids grids;           // load [N] and creepage grids
  Material material;
  NormalOptions normal;
  TangentialSettings tangential;
  CreepConditions creep;
  FastsimOptions fastsim;
  WearOptions wear;
  CoupledLoadOptions coupling;          // couple = false: the creep part has no normal outputs (format 1.0 layout)
  halfspace::HalfspaceOptions halfspace;  // normal model halfspace ([contact] element_size)
  std::vector<NormalModel> model_by_y;  // per node of the scene's y grid (planned model choice); empty = normal.model
  bool normalised = false;              // format 2.1 normalised creep coordinates (creep_map.hpp)
  std::array<double, 3> knee = {1.0, 1.0, 1.0};  // node map knee per creepage axis (scene.creep_knee)
  double law_spin = 0.0;  // the saturation law's spin weight (scene.creep_law_spin, creep_map.hpp)
  bool creep_coefficients = true;  // false: the normal part's creep_coefficient_* cells stay 0 (not computed)
  std::size_t creepages() const { return grids.xi.size() * grids.eta.size() * grids.phi.size(); }
};

// The creepage of creep grid node (ix, ie, ip): the grid's values, or with normalised coordinates
// the physical creepage of the node's v at the slot's scales (an unswept axis keeps its value).
inline Creepage node_creepage(const KernelData& k, std::size_t ix, std::size_t ie, std::size_t ip,
                       const creep_map::Scales* scales) {
  const SceneGrids& g = k.grids;
  if (!k.normalised || !scales) return Creepage{g.xi[ix], g.eta[ie], g.phi[ip]};
  // The knee k of m(x) = x / (k + |x|) is m(x / k): the map at scale s k.
  auto map = [](const std::vector<double>& axis, std::size_t i, double s) {
    if (axis.size() < 2) return axis.front();
    return creep_map::physical(creep_map::nodes(axis.size())[i], axis.front(), axis.back(), s);
  };
  return Creepage{map(g.xi, ix, scales->xi * k.knee[0]), map(g.eta, ie, scales->eta * k.knee[1]),
                  map(g.phi, ip, scales->phi * k.knee[2])};
}

// Format 2.1: the creep forces stored as F / (mu N) minus the saturation law at the node's
// normalised creepage, mz as mz / (mu N) [m] (creep_map.hpp); N is the creep point's own normal
// force. Zeros stay zeros (no load).
inline FastsimResult normalised_forces(const FastsimResult& r, const Creepage& c, double normal_force, double friction,
                                const creep_map::Scales& s, double law_spin) {
  FastsimResult out = r;
  if (!(normal_force > 0.0)) return out;
  const double mun = friction * normal_force;
  const std::array<double, 2> law = creep_map::law(c.xi / s.xi, c.eta / s.eta, c.phi / s.phi, law_spin);
  out.fx = r.fx / mun - law[0];
  out.fy = r.fy / mun - law[1];
  out.mz = r.mz / mun;
  return out;
}

// The normal options at this column (the planned model choice per y node).
inline NormalOptions uncoupled_options(const KernelData& k, const ColumnState& state) {
  NormalOptions options = k.normal;
  if (!k.model_by_y.empty()) options.model = k.model_by_y[state.iy];
  return options;
}

}  // namespace railtab::kernel
