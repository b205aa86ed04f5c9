// SPDX-License-Identifier: Apache-2.0
// Contact jumps along y (jump_locator.hpp): the contact configuration at every y node, then, in every
// cell whose end nodes differ in contact configuration (or whose contact point moves a lot),
// bisection to the tolerance.
#include "adaptive/jump_locator.hpp"


#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "adaptive/contact_probe.hpp"
#include "engine/mirror.hpp"
#include "engine/parallel_for.hpp"
#include "engine/progress.hpp"

namespace railtab {
namespace {

namespace pb = probe_slot_bits;

// What decides a jump at one (y, wheel, load): per slot the configuration bits and the contact
// positions (rolling radius of the rigid point and of the loaded patch).
struct Signature {
  std::uint32_t bits[2] = {0, 0};  // probe bits kGeometry, kGeometryTwo, kGeometryFirst, kLoaded
  double point_radius[2] = {0, 0};
  double patch_radius[2] = {0, 0};
};

constexpr std::uint32_t kConfigBits = pb::kGeometry | pb::kGeometryTwo | pb::kGeometryFirst | pb::kLoaded;

Signature signature(const ContactProbe::Wheel& w) {
  Signature s;
  for (int k = 0; k < 2; ++k) {
    const ContactProbe::Slot& slot = w.slot[k];
    s.bits[k] = slot.status & kConfigBits;
    s.point_radius[k] = slot.rolling_radius;
    s.patch_radius[k] = slot.patch_radius;
  }
  return s;
}

// Configuration kinds that differ between a and b (no position jumps).
std::uint32_t config_kind(const Signature& a, const Signature& b) {
  std::uint32_t kind = 0;
  for (int k = 0; k < 2; ++k) {
    const std::uint32_t d = a.bits[k] ^ b.bits[k];
    if (d & pb::kGeometry) kind |= jump_kind::kPointSlot0 << k;
    if (d & (pb::kGeometryTwo | pb::kGeometryFirst)) kind |= jump_kind::kSwitchSlot0 << k;
    if (d & pb::kLoaded) kind |= jump_kind::kPatchSlot0 << k;
  }
  return kind;
}

// Position changes between a and b, per (point slot 0, point slot 1, patch slot 0, patch slot 1);
// 0 where either end has no such contact.
std::array<double, 4> position_steps(const Signature& a, const Signature& b) {
  std::array<double, 4> d{};
  for (int k = 0; k < 2; ++k) {
    if ((a.bits[k] & b.bits[k]) & pb::kGeometry) d[k] = std::abs(a.point_radius[k] - b.point_radius[k]);
    if ((a.bits[k] & b.bits[k]) & pb::kLoaded) d[2 + k] = std::abs(a.patch_radius[k] - b.patch_radius[k]);
  }
  return d;
}

constexpr std::uint32_t kMoveKind[4] = {jump_kind::kPointMoveSlot0, jump_kind::kPointMoveSlot1,
                                        jump_kind::kPatchMoveSlot0, jump_kind::kPatchMoveSlot1};

class Bisection {
 public:
  Bisection(const ContactProbe& probe, std::size_t wheel, double load, const JumpLocatorOptions& options)
      : probe_(probe), wheel_(wheel), load_(load), options_(options) {}

  Signature at(double y) {
    ++evaluations_;
    return signature(probe_.configuration(y, wheel_, load_));
  }

  // Jumps in [a, b]. A configuration change is followed into every half that shows it. A position
  // step is followed only into a half holding more than 3/4 of the parent's step: a continuous
  // change splits about evenly and stops there, a discontinuity stays in one half down to the
  // tolerance, where it must still exceed radius_step.
  void find(double a, const Signature& sa, double b, const Signature& sb, const std::array<double, 4>& parent,
            std::vector<ContactJump>& out) {
    const std::uint32_t config = config_kind(sa, sb);
    const std::array<double, 4> steps = position_steps(sa, sb);
    std::uint32_t move = 0;
    for (int k = 0; k < 4; ++k)
      if (steps[k] > options_.radius_step && steps[k] > 0.75 * parent[k]) move |= kMoveKind[k];
    if (!config && !move) return;
    if (b - a <= options_.tolerance) {
      out.push_back({0.5 * (a + b), config | move, a, b});
      return;
    }
    std::array<double, 4> next{};
    for (int k = 0; k < 4; ++k) next[k] = (move & kMoveKind[k]) ? steps[k] : std::numeric_limits<double>::infinity();
    const double m = 0.5 * (a + b);
    const Signature sm = at(m);
    find(a, sa, m, sm, next, out);
    find(m, sm, b, sb, next, out);
  }

  std::size_t evaluations() const { return evaluations_; }

 private:
  const ContactProbe& probe_;
  std::size_t wheel_;
  double load_;
  const JumpLocatorOptions& options_;
  std::size_t evaluations_ = 0;
};

std::string fmt_jump_description(const JumpLocatorOptions& o) {
  return fmt::format("y of each contact jump of this wheel per load node, sorted; NaN = no further jump; located "
                     "by bisection to {:g} m (grid nodes lie outside that interval); a rolling-radius step above "
                     "{:g} m is a position jump",
                     o.tolerance, o.radius_step);
}

constexpr const char* kJumpKindDescription =
    "kind of each jump, bits: 1/2 rigid point appears or vanishes in slot 0/1, 4/8 rigid points compete for "
    "slot 0/1 or the kept one switches, 16/32 rigid point of slot 0/1 jumps, 64/128 loaded patch appears or "
    "vanishes in slot 0/1 (flange onset, lift-off), 256/512 loaded patch of slot 0/1 jumps; bits 1-32 are "
    "geometric (every part jumps), 64-512 only the normal, creep and wear parts; 0 = no jump";

// Moved in whole (assigning string literals member-wise trips GCC 12's -Wrestrict false positive).
TableDataset dataset(std::string name, std::string units, std::string description) {
  TableDataset d;
  d.name = std::move(name);
  d.units = std::move(units);
  d.description = std::move(description);
  return d;
}

// Jumps are located per load node at one roll and one yaw per y, with the scene's one normal model:
// not for a roll or yaw axis nor a per-y model choice (no jumps written: the lookup interpolates as
// before 2.1).
bool roll_is_axis(const Scene& scene) {
  return (!scene.equilibrium_roll && scene.grids.roll.size() > 1) || scene.grids.yaw.size() > 1 ||
         !scene.accuracy.model_by_y.empty();
}

}  // namespace

ContactJumps locate_jumps(const Scene& scene, const JumpLocatorOptions& options, int threads,
                          const StageProgress& progress, CellRange range) {
  ContactJumps result;
  const std::vector<double>& y = scene.grids.y;
  const std::vector<double>& loads = scene.grids.load;
  if (roll_is_axis(scene) || y.size() < 2 || loads.empty()) return result;
  const std::size_t first = std::min(range.first, y.size() - 1), last = std::clamp(range.last, first, y.size() - 1);
  const ContactProbe probe(scene);
  // The configuration at the cells' nodes, per wheel and load (no creep forces: the signature has
  // none); node k is y[first + k].
  const std::size_t n_load = loads.size(), cells = last - first, span = cells + 1, tasks = 2 * n_load * cells;
  // The mirror: the right wheel's cell i is the left wheel's cell n - 2 - i mirrored, where that
  // one is among the cells (task index of the left wheel's cell, or `tasks`).
  const bool mirrored = options.mirror && mirror_obstacle(scene).empty();
  std::vector<std::size_t> image(tasks, tasks);
  for (std::size_t task = n_load * cells; mirrored && task < tasks; ++task) {
    const std::size_t l = (task / cells) % n_load, i = first + task % cells, c = y.size() - 2 - i;
    if (c >= first && c < last) image[task] = l * cells + (c - first);
  }
  std::vector<std::size_t> computed;  // the cells bisected, and the nodes they start from
  std::vector<char> node_used(cells > 0 ? 2 * n_load * span : 0, 0);  // [wheel][load][node]
  for (std::size_t task = 0; task < tasks; ++task) {
    if (image[task] != tasks) continue;
    computed.push_back(task);
    const std::size_t wheel = task / (n_load * cells), l = (task / cells) % n_load, k = task % cells;
    node_used[(wheel * n_load + l) * span + k] = node_used[(wheel * n_load + l) * span + k + 1] = 1;
  }
  std::vector<std::size_t> used;
  for (std::size_t t = 0; t < node_used.size(); ++t)
    if (node_used[t]) used.push_back(t);
  std::vector<Signature> nodes(node_used.size());
  std::vector<std::vector<ContactJump>> found(tasks);
  std::vector<std::size_t> spent(tasks, 0);
  TaskProgress ticks(progress, used.size() + computed.size());  // nodes, then cells (most without a jump)
  parallel_for_index(threads, used.size(), [&](std::size_t u) {
    const std::size_t t = used[u], wheel = t / (n_load * span), l = (t / span) % n_load, i = first + t % span;
    nodes[t] = signature(probe.configuration(y[i], wheel, loads[l]));
    ticks.tick();
  });
  parallel_for_index(threads, computed.size(), [&](std::size_t c) {
    const std::size_t task = computed[c];
    const std::size_t wheel = task / (n_load * cells), l = (task / cells) % n_load, k = task % cells, i = first + k;
    const std::size_t node = (wheel * n_load + l) * span + k;
    Bisection bisection(probe, wheel, loads[l], options);
    bisection.find(y[i], nodes[node], y[i + 1], nodes[node + 1], {}, found[task]);
    spent[task] = bisection.evaluations();
    ticks.tick();
  });
  ticks.finish();
  for (std::size_t task = 0; task < tasks; ++task) {
    if (image[task] == tasks) continue;
    const std::vector<ContactJump>& from = found[image[task]];
    for (auto j = from.rbegin(); j != from.rend(); ++j) found[task].push_back({-j->y, j->kind, -j->right, -j->left});
  }
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    result.wheel[wheel].resize(n_load);
    for (std::size_t l = 0; l < n_load; ++l)
      for (std::size_t i = 0; i < cells; ++i) {
        const std::vector<ContactJump>& f = found[(wheel * n_load + l) * cells + i];
        result.wheel[wheel][l].insert(result.wheel[wheel][l].end(), f.begin(), f.end());
      }
  }
  result.evaluations = used.size();
  for (std::size_t s : spent) result.evaluations += s;
  return result;
}

void add_jumps(Table& table, const Scene& scene, const ContactJumps& jumps, const JumpLocatorOptions& options,
               int threads, const StageProgress& progress, const std::string& root) {
  if (roll_is_axis(scene)) return;
  std::size_t count = 0;
  for (const auto& wheel : jumps.wheel)
    for (const auto& list : wheel) count = std::max(count, list.size());
  if (count == 0) return;  // no jumps: no group (the lookup then interpolates as before 2.1)
  const bool load_axis = table.axis("load") != nullptr;
  const std::size_t n_load = jumps.wheel[0].size();
  TableGroup group{root, {}};
  const char* names[2] = {"left", "right"};
  for (std::size_t w = 0; w < 2; ++w) {
    TableDataset y = dataset(std::string(names[w]) + "_y", std::string("m"), fmt_jump_description(options));
    TableDataset kind = dataset(std::string(names[w]) + "_kind", std::string("1"), std::string(kJumpKindDescription));
    kind.is_status = true;
    for (TableDataset* d : {&y, &kind}) {
      d->axes = load_axis ? std::vector<std::string>{"load", kJumpDimension} : std::vector<std::string>{kJumpDimension};
      d->shape = load_axis ? std::vector<std::size_t>{n_load, count} : std::vector<std::size_t>{count};
    }
    y.values.assign(n_load * count, std::numeric_limits<double>::quiet_NaN());
    kind.status.assign(n_load * count, 0u);
    for (std::size_t l = 0; l < n_load; ++l)
      for (std::size_t j = 0; j < jumps.wheel[w][l].size(); ++j) {
        y.values[l * count + j] = jumps.wheel[w][l][j].y;
        kind.status[l * count + j] = jumps.wheel[w][l][j].kind;
      }
    group.datasets.push_back(std::move(y));
    group.datasets.push_back(std::move(kind));
  }
  table.groups.push_back(std::move(group));
  add_jump_samples(table, scene, jumps, threads, progress, root, options.mirror);
}

}  // namespace railtab
