#include "contact_kernel.hpp"

#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "geometry/contact_geometry.hpp"
#include "normal/normal_model.hpp"

namespace railtab {
namespace {

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
const Output<ContactPoint> kGeometryOutputs[] = {
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
const Output<ContactPatch> kNormalOutputs[] = {
    {"normal_force", "N", "normal force along the contact normal", [](const ContactPatch& c) { return c.normal_force; }},
    {"approach", "m", "normal approach at the patch reference point", [](const ContactPatch& c) { return c.penetration; }},
    {"area", "m2", "contact area", [](const ContactPatch& c) { return c.area; }},
    {"max_pressure", "Pa", "maximum contact pressure", [](const ContactPatch& c) { return c.max_pressure; }},
    {"a", "m", "rolling semi-axis (elliptic models; 0 for non-elliptic patches)",
     [](const ContactPatch& c) { return c.semi_axis_a; }},
    {"b", "m", "lateral semi-axis (elliptic models; 0 for non-elliptic patches)",
     [](const ContactPatch& c) { return c.semi_axis_b; }},
};

// HOOK(creep, wear): the tangential (src/tangential/fastsim.hpp) and wear (src/wear/) layers are
// being written. When they land: add kCreepOutputs (fx, fy, mz, slip_fraction from FastsimResult)
// and kWearOutputs (wear_rate from WearResult) tables like the two above, a PartSpec each with
// inner axes {load, xi, eta, phi} in make_contact_kernel, and in solve_wheel_column one loop over
// the creepages per loaded patch after the normal part. Until then no creep/wear part is written.

template <class Result, std::size_t N>
PartSpec part_spec(const char* name, std::vector<std::string> inner_axes, const Output<Result> (&outputs)[N]) {
  PartSpec spec{name, std::move(inner_axes), {}};
  for (const Output<Result>& o : outputs) spec.outputs.push_back({o.name, o.units, o.description});
  return spec;
}

template <class Result, std::size_t N>
void store(const Output<Result> (&outputs)[N], const Result& result, const ColumnOutput& out, std::size_t wheel,
           std::size_t part, std::size_t cell) {
  for (std::size_t o = 0; o < N; ++o) out.values(wheel, part, o)[cell] = outputs[o].get(result);
}

constexpr std::size_t kGeometryPart = 0;
constexpr std::size_t kNormalPart = 1;

// A point where the core threw: no values (zeros), and a status without kConverged.
StatusBits failure_status(const ColumnState& state) {
  bool bad_input = !std::isfinite(state.y) || !std::isfinite(state.roll);
  return status::kNotConverged | (bad_input ? status::kInvalidInput : 0u);
}

struct KernelData {
  ContactGeometrySolver solver;
  std::vector<double> loads;  // [N]
  Material material;
  NormalOptions normal;
};

void solve_wheel_column(const KernelData& k, const ColumnState& state, std::size_t wheel, ColumnOutput& out) {
  const Side side = wheel == 0 ? Side::left : Side::right;
  const std::size_t nload = k.loads.size();
  WheelContactGeometry geometry;
  try {
    geometry = k.solver.solve_wheel(side, WheelsetState{state.y, state.roll});
  } catch (const std::exception& e) {
    out.failure(fmt::format("geometry, {} wheel, y = {} m, roll = {} rad: {}", to_string(side), state.y,
                            state.roll, e.what()));
    for (std::size_t s = 0; s < kSlots; ++s) out.status(wheel, kGeometryPart)[s] = failure_status(state);
    for (std::size_t c = 0; c < nload * kSlots; ++c) out.status(wheel, kNormalPart)[c] = failure_status(state);
    return;
  }
  const SlotAssignment slots = assign_slots(geometry);
  const StatusBits wheel_bits = geometry.status & (status::kTwoPoint | status::kProfileEdge);
  for (std::size_t s = 0; s < kSlots; ++s) {
    if (slots.point[s] < 0) continue;  // empty slot: zeros, status 0
    const ContactPoint& p = geometry.points[static_cast<std::size_t>(slots.point[s])];
    store(kGeometryOutputs, p, out, wheel, kGeometryPart, s);
    out.status(wheel, kGeometryPart)[s] = p.status | status::kConverged | wheel_bits | slots.extra[s];
  }

  for (std::size_t il = 0; il < nload; ++il) {
    WheelNormalResult normal;
    try {
      normal = solve_normal_for_load(geometry, k.loads[il], k.material, k.normal);
    } catch (const std::exception& e) {
      out.failure(fmt::format("normal, {} wheel, y = {} m, roll = {} rad, load = {} N: {}", to_string(side),
                              state.y, state.roll, k.loads[il], e.what()));
      for (std::size_t s = 0; s < kSlots; ++s) out.status(wheel, kNormalPart)[il * kSlots + s] = failure_status(state);
      continue;
    }
    const StatusBits solver_bits = normal.status & (status::kConverged | status::kNotConverged);
    for (std::size_t s = 0; s < kSlots; ++s) {
      auto index = static_cast<std::size_t>(slots.point[s]);
      if (slots.point[s] < 0 || index >= normal.patches.size()) continue;
      const ContactPatch& patch = normal.patches[index];
      store(kNormalOutputs, patch, out, wheel, kNormalPart, il * kSlots + s);
      out.status(wheel, kNormalPart)[il * kSlots + s] = patch.status | solver_bits | slots.extra[s];
    }
    // HOOK(creep, wear): creepage loop over the loaded patches goes here.
  }
}

}  // namespace

SlotAssignment assign_slots(const WheelContactGeometry& geometry) {
  SlotAssignment a;
  for (std::size_t i = 0; i < geometry.points.size(); ++i) {
    const ContactPoint& p = geometry.points[i];
    std::size_t slot = (p.status & status::kFlangeContact) ? 1 : 0;
    int& current = a.point[slot];
    if (current < 0) {
      current = static_cast<int>(i);
      continue;
    }
    a.extra[slot] |= status::kTwoPoint;
    if (p.separation < geometry.points[static_cast<std::size_t>(current)].separation) current = static_cast<int>(i);
  }
  return a;
}

SweepKernel make_contact_kernel(const Scene& scene) {
  auto data = std::make_shared<const KernelData>(
      KernelData{make_geometry_solver(scene), scene.grids.load, scene.material, scene.normal});
  SweepKernel kernel;
  kernel.parts.push_back(part_spec("geometry", {}, kGeometryOutputs));
  kernel.parts.push_back(part_spec("normal", {"load"}, kNormalOutputs));
  kernel.points_per_column = scene.grids.load.size();
  const NormalOptions& n = scene.normal;
  kernel.models = {
      {"normal", to_string(n.model)},
      {"negative_curvature", to_string(n.negative_curvature)},
      {"strips", n.strips},
      {"virtual_penetration", n.virtual_penetration},
      {"normal_tolerance", n.tolerance},
      {"flange_angle", scene.geometry.flange_angle},
      {"youngs_modulus", scene.material.youngs_modulus},
      {"poisson_ratio", scene.material.poisson_ratio},
  };
  kernel.equilibrium_roll = [data](double y) { return data->solver.equilibrium_roll(y); };
  kernel.compute = [data](const ColumnState& state, ColumnOutput& out) {
    for (std::size_t wheel = 0; wheel < 2; ++wheel) solve_wheel_column(*data, state, wheel, out);
  };
  return kernel;
}

}  // namespace railtab
