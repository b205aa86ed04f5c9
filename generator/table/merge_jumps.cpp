// SPDX-License-Identifier: Apache-2.0
// Joins the contact jumps the shards located in their own y cells (group shard_jumps) into the
// single run's /jumps group and its one-sided values (docs/table-format.md, "Contact jumps").
#include "table/merge_jumps.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/check.hpp"

namespace railtab {
namespace {

constexpr const char* kWheels[2] = {"left", "right"};

bool under(const std::string& path, const std::string& root) {
  return path == root || path.rfind(root + "/", 0) == 0;
}

// The jump count of each load node of one wheel's list (<wheel>_y over ([load,] jump), NaN after
// the last jump), checked: finite and increasing before the padding, only padding after it.
std::vector<std::size_t> list_counts(const TableDataset& y, const TableDataset& kind, std::size_t n_load,
                                     const std::string& where) {
  const std::size_t width = y.shape.empty() ? 0 : y.shape.back();
  RAILTAB_CHECK(!y.is_status && kind.is_status && y.shape == kind.shape && y.values.size() == n_load * width &&
                    (y.shape.size() == 1 || y.shape.front() == n_load),
                "merge: {}: {} and its kinds are malformed", where, y.name);
  std::vector<std::size_t> counts(n_load, 0);
  for (std::size_t l = 0; l < n_load; ++l) {
    double last = -std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < width; ++j) {
      const double v = y.values[l * width + j];
      const bool padding = std::isnan(v);
      if (padding && kind.status[l * width + j] == 0) continue;
      RAILTAB_CHECK(!padding && std::isfinite(v) && v > last && counts[l] == j && kind.status[l * width + j] != 0,
                    "merge: {}: {} holds a non-finite, unordered or misplaced jump at load node {}, entry {}", where,
                    y.name, l, j);
      last = v;
      ++counts[l];
    }
  }
  return counts;
}

// A dataset of `merged` shaped as `like` with its jump dimension (`jump_dim`) `count` long, filled
// with `fill` (0 for values and kinds, NaN for the jump positions).
TableDataset resized(const TableDataset& like, std::size_t jump_dim, std::size_t count, double fill) {
  TableDataset d;
  d.name = like.name;
  d.units = like.units;
  d.description = like.description;
  d.axes = like.axes;
  d.shape = like.shape;
  d.shape[jump_dim] = count;
  d.is_status = like.is_status;
  if (d.is_status) d.status.assign(d.size(), 0u);
  else d.values.assign(d.size(), fill);
  return d;
}

}  // namespace

void join_shard_jumps(const std::vector<const Table*>& shards, const std::vector<std::string>& names, Table& merged) {
  // Each shard's groups under shard_jumps (absent: no jump in its cells).
  const std::string root = kShardJumpGroup;
  const Table* model = nullptr;  // the first shard with jumps: the layout every other must have
  for (const Table* t : shards)
    if (!model && t->group(root)) model = t;
  if (!model) return;  // no jump anywhere: no /jumps, as a single run
  const TableDataset* first_y = model->group(root)->find("left_y");
  RAILTAB_CHECK(first_y && !first_y->shape.empty(), "merge: /{} lacks left_y", root);
  const std::size_t n_load = first_y->shape.size() == 2 ? first_y->shape.front() : 1;
  const std::size_t jump_dim = first_y->shape.size() - 1;  // in the lists; the samples' too

  // counts[shard][wheel][load] and where each shard's jumps start in the joined lists.
  std::vector<std::array<std::vector<std::size_t>, 2>> counts(shards.size()), offsets(shards.size());
  std::size_t count = 0;
  for (std::size_t w = 0; w < 2; ++w) {
    std::vector<std::size_t> total(n_load, 0);
    for (std::size_t s = 0; s < shards.size(); ++s) {
      counts[s][w].assign(n_load, 0);
      offsets[s][w] = total;
      const TableGroup* list = shards[s]->group(root);
      if (!list) continue;
      const TableDataset* y = list->find(std::string(kWheels[w]) + "_y");
      const TableDataset* kind = list->find(std::string(kWheels[w]) + "_kind");
      RAILTAB_CHECK(y && kind && y->axes == first_y->axes, "merge: {}: /{} is missing {}_y or {}_kind, or has other axes",
                    names[s], root, kWheels[w], kWheels[w]);
      counts[s][w] = list_counts(*y, *kind, n_load, names[s]);
      for (std::size_t l = 0; l < n_load; ++l) total[l] += counts[s][w][l];
    }
    for (std::size_t n : total) count = std::max(count, n);
  }
  if (count == 0) return;

  // The groups in the model shard's order (the lists, then <wheel>/<part>), renamed to /jumps.
  for (const TableGroup& g : model->groups) {
    if (!under(g.path, root)) continue;
    const bool is_list = g.path == root;
    const std::size_t w = g.path.rfind(root + "/right/", 0) == 0 ? 1 : 0;
    TableGroup out{kJumpGroup + g.path.substr(root.size()), {}};
    for (const TableDataset& like : g.datasets) {
      RAILTAB_CHECK(like.shape.size() > jump_dim, "merge: {}: /{}/{} has no jump dimension", names[0], g.path, like.name);
      const bool positions = is_list && !like.is_status;
      const std::size_t lw = is_list ? (like.name.rfind("right", 0) == 0 ? 1 : 0) : w;
      TableDataset d = resized(like, jump_dim, count, positions ? std::numeric_limits<double>::quiet_NaN() : 0.0);
      std::size_t block = 1;  // values of one (load, jump): side x creepages x slot in the samples
      for (std::size_t k = jump_dim + 1; k < like.shape.size(); ++k) block *= like.shape[k];
      for (std::size_t s = 0; s < shards.size(); ++s) {
        const TableGroup* sg = shards[s]->group(g.path);
        bool none = true;
        for (std::size_t n : counts[s][lw]) none = none && n == 0;
        if (none && !sg) continue;
        const TableDataset* src = sg ? sg->find(like.name) : nullptr;
        RAILTAB_CHECK(src && src->axes == like.axes && src->is_status == like.is_status &&
                          (jump_dim == 0 || src->shape.front() == n_load) &&
                          std::equal(src->shape.begin() + static_cast<std::ptrdiff_t>(jump_dim) + 1, src->shape.end(),
                                     like.shape.begin() + static_cast<std::ptrdiff_t>(jump_dim) + 1, like.shape.end()),
                      "merge: {}: /{}/{} is missing or shaped differently", names[s], g.path, like.name);
        const std::size_t width = src->shape[jump_dim];
        for (std::size_t l = 0; l < n_load; ++l) {
          RAILTAB_CHECK(counts[s][lw][l] <= width, "merge: {}: /{}/{} holds fewer jumps than its list", names[s], g.path,
                        like.name);
          const std::size_t from = (l * width) * block, to = (l * count + offsets[s][lw][l]) * block;
          const std::size_t n = counts[s][lw][l] * block;
          if (d.is_status) {
            std::copy_n(src->status.begin() + static_cast<std::ptrdiff_t>(from), n,
                        d.status.begin() + static_cast<std::ptrdiff_t>(to));
          } else {
            std::copy_n(src->values.begin() + static_cast<std::ptrdiff_t>(from), n,
                        d.values.begin() + static_cast<std::ptrdiff_t>(to));
          }
        }
      }
      out.datasets.push_back(std::move(d));
    }
    merged.groups.push_back(std::move(out));
  }
}

}  // namespace railtab
