// SPDX-License-Identifier: Apache-2.0
// The load-balance rule of low_confidence (low_confidence.hpp): nodes and one-sided jump values
// whose normal forces and contact angles do not carry the wheel's vertical load.
#include "low_confidence.hpp"

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "table_data.hpp"

namespace railtab::lookup::detail {
namespace {

// Index of the block holding `part`, -1 if none.
int block_with(const TableData& d, int part) {
  for (int b = 0; b < d.n_blocks; ++b)
    for (int p = 0; p < d.block[0][b].n_parts; ++p)
      if (d.block[0][b].part[p] == part) return b;
  return -1;
}

int value_of(const Block& b, int output) {
  for (int k = 0; k < b.n_values; ++k)
    if (b.output_of[k] == output) return k;
  return -1;
}

// Whether block b's dimensions are exactly `vars` (in order).
bool block_over(const Block& b, std::initializer_list<int> vars) {
  if (b.n_dims != static_cast<int>(vars.size())) return false;
  int k = 0;
  for (int v : vars)
    if (b.var[k++] != v) return false;
  return true;
}

void or_status(unsigned char* record, const Block& b) {
  for (int p = 0; p < b.n_parts; ++p) {
    StatusBits s;
    unsigned char* at = record + b.status_offset + static_cast<std::size_t>(p) * sizeof s;
    std::memcpy(&s, at, sizeof s);
    s |= status::kLowConfidence;
    std::memcpy(at, &s, sizeof s);
  }
}

// |sum over slots of N cos(angle) - load| > kLoadBalanceLimit load (docs/lookup.md).
bool unbalanced(const double* normal_force, const double* angle, int n_slots, double load) {
  double carried = 0.0;
  for (int s = 0; s < n_slots; ++s) carried += normal_force[s] * std::cos(angle[s]);
  return std::abs(carried - load) > kLoadBalanceLimit * load;
}

}  // namespace

void mark_unbalanced_load(TableData& d) {
  // Format 2.1 and later (TableData::load_controlled): the balance is the model's own.
  if (!d.load_controlled) return;
  const int gb = block_with(d, kGeometry), nb = block_with(d, kNormal);
  if (gb < 0 || nb < 0 || d.n_slots > kMaxSlots) return;
  // Only the shape whose geometry depends on y alone and whose normal contact on y and load (roll
  // following the equilibrium or fixed): other shapes keep the presence rules only.
  const bool load_axis = d.tabulated[kVarLoad];
  if (!block_over(d.block[0][gb], {kVarY})) return;
  if (!block_over(d.block[0][nb], load_axis ? std::initializer_list<int>{kVarY, kVarLoad}
                                            : std::initializer_list<int>{kVarY}))
    return;
  const int angle_k = value_of(d.block[0][gb], kContactAngle), force_k = value_of(d.block[0][nb], kNormalForce);
  if (angle_k < 0 || force_k < 0) return;
  const int ny = d.axis[kVarY].size();
  const int nl = load_axis ? d.axis[kVarLoad].size() : 1;
  auto load_at = [&](int l) { return load_axis ? d.axis[kVarLoad].nodes()[l] : d.fixed_value[kVarLoad]; };
  // Blocks whose records get the bit: every block but the geometry's, unless it holds the normal
  // part too (load fixed). Their y and load dimensions come first, in that order (the file's: y,
  // roll, load, creepages).
  std::vector<int> marked;
  for (int b = 0; b < d.n_blocks; ++b)
    if (b != gb || gb == nb) marked.push_back(b);
  for (int w = 0; w < 2; ++w) {
    const Block& g = d.block[w][gb];
    const Block& n = d.block[w][nb];
    double force[kMaxSlots], angle[kMaxSlots];
    // Grid nodes: every cell that has the node as a corner.
    for (int i = 0; i < ny; ++i)
      for (int l = 0; l < nl; ++l) {
        for (int s = 0; s < d.n_slots; ++s) {
          angle[s] = record_value<double>(g.data.data() + s * g.slot_size + i * g.stride[0], angle_k);
          force[s] = record_value<double>(
              n.data.data() + s * n.slot_size + i * n.stride[0] + (load_axis ? l * n.stride[1] : 0), force_k);
        }
        if (!unbalanced(force, angle, d.n_slots, load_at(l))) continue;
        for (int b : marked) {
          Block& m = d.block[w][b];
          const int load_dim = load_axis ? 1 : -1;
          std::size_t inner = 1;  // records per (y, load) node: the creepage axes
          for (int k = load_axis ? 2 : 1; k < m.n_dims; ++k) inner *= static_cast<std::size_t>(m.size[k]);
          for (int s = 0; s < d.n_slots; ++s) {
            if (!(force[s] > 0.0)) continue;
            for (int ci = i - 1; ci <= i; ++ci)
              for (int cl = load_axis ? l - 1 : 0; cl <= (load_axis ? l : 0); ++cl) {
                if (ci < 0 || ci > ny - 2 || cl < 0 || (load_axis && cl > nl - 2)) continue;
                unsigned char* first = m.data.data() + s * m.slot_size + ci * m.stride[0] +
                                       (load_dim >= 0 ? cl * m.stride[1] : 0);
                for (std::size_t r = 0; r < inner; ++r) or_status(first + r * static_cast<std::size_t>(m.record), m);
              }
          }
        }
      }
    if (!d.has_jumps) continue;
    // One-sided values at the jumps: the geometry's and the normal part's at the same end.
    JumpWheel& j = d.jumps[w];
    const JumpSamples& gs = j.samples[gb];
    const JumpSamples& ns = j.samples[nb];
    for (std::size_t l = 0; l < j.n_load_nodes; ++l)
      for (std::size_t k = 0; k < j.y[0][l].size(); ++k)
        for (std::size_t side = 0; side < 2; ++side) {
          for (int s = 0; s < d.n_slots; ++s) {
            angle[s] = record_value<double>(gs.data.data() + s * gs.slot_stride + l * gs.load_stride +
                                                k * gs.jump_stride + side * gs.side_stride,
                                            angle_k);
            force[s] = record_value<double>(ns.data.data() + s * ns.slot_stride + l * ns.load_stride +
                                                k * ns.jump_stride + side * ns.side_stride,
                                            force_k);
          }
          if (!unbalanced(force, angle, d.n_slots, load_at(static_cast<int>(l)))) continue;
          for (int b : marked) {
            JumpSamples& ms = j.samples[b];
            const Block& m = d.block[w][b];
            const std::size_t records = ms.side_stride / static_cast<std::size_t>(m.record);
            for (int s = 0; s < d.n_slots; ++s) {
              if (!(force[s] > 0.0)) continue;
              unsigned char* first = ms.data.data() + s * ms.slot_stride + l * ms.load_stride + k * ms.jump_stride +
                                     side * ms.side_stride;
              for (std::size_t r = 0; r < records; ++r) or_status(first + r * static_cast<std::size_t>(m.record), m);
            }
          }
        }
  }
}

}  // namespace railtab::lookup::detail
