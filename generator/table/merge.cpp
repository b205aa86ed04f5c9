// SPDX-License-Identifier: Apache-2.0
// Joins table shards (generate --shard I/N) into one table, checking they fit together.
#include "table/merge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <numeric>

#include "core/check.hpp"
#include "table/merge_jumps.hpp"
#include "table/table_io.hpp"

namespace railtab {
namespace {

// The shard's jumps (group shard_jumps and below): joined by join_shard_jumps, not along y.
bool is_jump_group(const TableGroup& g) {
  const std::string root = kShardJumpGroup;
  return g.path == root || g.path.rfind(root + "/", 0) == 0;
}

// Groups joined along y (the wheel parts, the root datasets).
std::size_t joined_groups(const Table& t) {
  return static_cast<std::size_t>(std::count_if(t.groups.begin(), t.groups.end(),
                                                [](const TableGroup& g) { return !is_jump_group(g); }));
}

// The first dataset of `t` holding a NaN or an infinity ("" when none): every output and one-sided
// value; not /equilibrium_roll (NaN where the roll search failed, by design) nor the jump
// positions (NaN padding, checked by join_shard_jumps).
std::string first_non_finite(const Table& t) {
  for (const TableGroup& g : t.groups) {
    for (const TableDataset& d : g.datasets) {
      if (d.name == "equilibrium_roll" || (g.path == kShardJumpGroup && !d.is_status)) continue;
      if (!std::all_of(d.values.begin(), d.values.end(), [](double v) { return std::isfinite(v); }))
        return "/" + (g.path.empty() ? d.name : g.path + "/" + d.name);
    }
  }
  return "";
}

struct ShardId {
  int index = 0;
  int count = 0;
  std::size_t y_begin = 0, y_end = 0, y_total = 0;
};

std::size_t to_size(const std::string* text, const std::string& name, const std::string& attr) {
  RAILTAB_CHECK(text, "{}: not a shard (no '{}' attribute); merge joins files written with --shard", name, attr);
  try {
    return static_cast<std::size_t>(std::stoull(*text));
  } catch (const std::exception&) {
    throw Error(fmt::format("{}: malformed attribute {} = \"{}\"", name, attr, *text));
  }
}

ShardId shard_id(const Table& t, const std::string& name) {
  const std::string* shard = t.attribute("shard");
  RAILTAB_CHECK(shard, "{}: not a shard (no 'shard' attribute); merge joins files written with --shard", name);
  ShardId id;
  RAILTAB_CHECK(std::sscanf(shard->c_str(), "%d/%d", &id.index, &id.count) == 2 && id.index >= 1 &&
                    id.index <= id.count,
                "{}: malformed shard attribute \"{}\"", name, *shard);
  id.y_begin = to_size(t.attribute("shard_y_begin"), name, "shard_y_begin");
  id.y_end = to_size(t.attribute("shard_y_end"), name, "shard_y_end");
  id.y_total = to_size(t.attribute("shard_y_total"), name, "shard_y_total");
  return id;
}

}  // namespace

Table merge_shards(const std::vector<Table>& shards, const std::vector<std::string>& names) {
  RAILTAB_CHECK(!shards.empty() && shards.size() == names.size(), "merge: no shards given");
  std::vector<ShardId> ids;
  for (std::size_t i = 0; i < shards.size(); ++i) ids.push_back(shard_id(shards[i], names[i]));
  const int count = ids[0].count;
  RAILTAB_CHECK(static_cast<std::size_t>(count) == shards.size(), "merge: {} is shard {}/{} but {} file(s) given",
                names[0], ids[0].index, count, shards.size());

  std::vector<std::size_t> order(shards.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a].index < ids[b].index; });
  const Table& first = shards[order[0]];
  std::size_t expected_begin = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Table& t = shards[order[k]];
    const ShardId& id = ids[order[k]];
    const std::string& name = names[order[k]];
    RAILTAB_CHECK(id.count == count, "merge: {} is a shard of {} but {} of {}", name, id.count, names[order[0]], count);
    RAILTAB_CHECK(id.index == static_cast<int>(k) + 1, "merge: shard {}/{} is missing or given twice (at {})",
                  k + 1, count, name);
    RAILTAB_CHECK(id.y_begin == expected_begin && id.y_end > id.y_begin && id.y_total == ids[order[0]].y_total,
                  "merge: {}: y range [{}, {}) does not continue the previous shards", name, id.y_begin, id.y_end);
    expected_begin = id.y_end;
    // The y values themselves continue the previous shards: otherwise the merged axis would not
    // be increasing and only the written table's check would say so, naming the output.
    const TableAxis* y = t.axis("y");
    RAILTAB_CHECK(y && y->values.size() == id.y_end - id.y_begin, "merge: {}: holds {} y values, its y range [{}, {}) needs {}",
                  name, y ? y->values.size() : 0, id.y_begin, id.y_end, id.y_end - id.y_begin);
    for (std::size_t i = 1; i < y->values.size(); ++i)
      RAILTAB_CHECK(y->values[i] > y->values[i - 1], "merge: {}: its y values are not increasing: y = {} m after {} m",
                    name, y->values[i], y->values[i - 1]);
    if (k > 0) {
      const std::string& before = names[order[k - 1]];
      const double last = shards[order[k - 1]].axis("y")->values.back();
      RAILTAB_CHECK(y->values.front() > last,
                    "merge: {}: its y values do not continue the previous shards: its first y = {} m is not above "
                    "y = {} m, the last of {}",
                    name, y->values.front(), last, before);
    }
    // Shards written before the shards carried their jumps would merge into a table without them
    // (different answers near a jump): refused.
    RAILTAB_CHECK(t.attribute("shard_jumps"),
                  "merge: {}: this shard carries no contact jumps of its y cells (written by an older railtab): "
                  "generate the shards again",
                  name);
    for (const char* attr : {"format_version", "scene", "models", "fixed_axes", "railtab_version", "git_commit",
                             "shard_jumps"}) {
      const std::string* a = t.attribute(attr);
      const std::string* b = first.attribute(attr);
      RAILTAB_CHECK(a && b && *a == *b, "merge: {} differs from {} in '{}' (not shards of one run)", name,
                    names[order[0]], attr);
    }
    RAILTAB_CHECK(t.axes.size() == first.axes.size() && joined_groups(t) == joined_groups(first),
                  "merge: {} has another layout than {}", name, names[order[0]]);
  }
  RAILTAB_CHECK(expected_begin == ids[order[0]].y_total, "merge: the shards cover {} of {} y values", expected_begin,
                ids[order[0]].y_total);

  Table merged = first;
  for (const char* attr : {"shard", "shard_y_begin", "shard_y_end", "shard_y_total", "shard_jumps"})
    merged.remove_attribute(attr);
  std::erase_if(merged.groups, [](const TableGroup& g) { return is_jump_group(g); });
  merged.set_attribute("created", utc_timestamp());
  for (TableAxis& axis : merged.axes) {
    for (std::size_t k = 1; k < order.size(); ++k) {
      const TableAxis* other = shards[order[k]].axis(axis.name);
      RAILTAB_CHECK(other, "merge: {} lacks axis {}", names[order[k]], axis.name);
      if (axis.name == "y") {
        axis.values.insert(axis.values.end(), other->values.begin(), other->values.end());
      } else {
        RAILTAB_CHECK(other->values == axis.values, "merge: {}: axis {} differs", names[order[k]], axis.name);
      }
    }
  }
  for (TableGroup& group : merged.groups) {
    for (TableDataset& d : group.datasets) {
      RAILTAB_CHECK(!d.axes.empty() && d.axes.front() == "y", "merge: /{}/{} has no y dimension to join along",
                    group.path, d.name);
      for (std::size_t k = 1; k < order.size(); ++k) {
        const TableGroup* g = shards[order[k]].group(group.path);
        const TableDataset* o = g ? g->find(d.name) : nullptr;
        RAILTAB_CHECK(o && o->axes == d.axes && o->is_status == d.is_status &&
                          std::equal(o->shape.begin() + 1, o->shape.end(), d.shape.begin() + 1, d.shape.end()),
                      "merge: {}: /{}/{} is missing or shaped differently", names[order[k]], group.path, d.name);
        // y is the slowest dimension: joining along y is appending.
        d.values.insert(d.values.end(), o->values.begin(), o->values.end());
        d.status.insert(d.status.end(), o->status.begin(), o->status.end());
        d.shape[0] += o->shape[0];
      }
      d.storage_bytes = 0;
    }
  }
  std::vector<const Table*> in_order;
  std::vector<std::string> ordered_names;
  for (std::size_t k : order) in_order.push_back(&shards[k]), ordered_names.push_back(names[k]);
  join_shard_jumps(in_order, ordered_names, merged);
  return merged;
}

std::size_t merge_table_files(const std::vector<std::string>& inputs, const std::string& output,
                              const MergeFinish& finish) {
  std::vector<std::filesystem::path> input_paths(inputs.begin(), inputs.end());
  check_output_path(output, input_paths);  // before reading: an input is never overwritten
  std::vector<Table> shards;
  for (const std::string& path : inputs) {
    shards.push_back(read_table(path));
    // A value the lookup would refuse is named with its shard here, not later in the merged table
    // (whose own load by the lookup, write_table's check, stays the last word).
    const std::string where = first_non_finite(shards.back());
    RAILTAB_CHECK(where.empty(), "merge: {}: dataset {} holds a non-finite value (the generator never writes one: "
                  "the shard was altered or damaged); generate this shard again", path, where);
  }
  const std::string* kernel = shards.front().attribute("shard_jumps");
  const bool contact_kernel = kernel && *kernel == "located";
  Table merged = merge_shards(shards, inputs);
  shards.clear();  // the shards' memory before writing
  if (finish && contact_kernel) {
    const std::filesystem::path stage = output + ".merge-stage";
    check_output_path(stage, input_paths);
    write_table(merged, stage, nullptr, input_paths);
    try {
      finish(merged, stage);
    } catch (...) {
      std::error_code ignored;
      std::filesystem::remove(stage, ignored);
      throw;
    }
    std::error_code ignored;
    std::filesystem::remove(stage, ignored);
  }
  write_table(merged, output, nullptr, input_paths);
  return merged.axis("y") ? merged.axis("y")->values.size() : 1;
}

}  // namespace railtab
