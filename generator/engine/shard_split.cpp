// SPDX-License-Identifier: Apache-2.0
// --shard: cost-balanced contiguous y ranges and the Slurm job-array form.
#include "engine/shard_split.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <numeric>

#include "core/check.hpp"

namespace railtab {

std::pair<std::size_t, std::size_t> weighted_shard_range(const std::vector<double>& costs, int index, int count) {
  const std::size_t ny = costs.size();
  RAILTAB_CHECK(count >= 1 && index >= 1 && index <= count, "shard {}/{}: need 1 <= I <= N", index, count);
  RAILTAB_CHECK(static_cast<std::size_t>(count) <= ny, "shard {}/{}: the y grid has only {} values to split", index,
                count, ny);
  std::vector<double> cumulative(ny + 1, 0.0);
  std::partial_sum(costs.begin(), costs.end(), cumulative.begin() + 1);
  // Boundary k (0 < k < count) is the column where the running cost first reaches k/count of the
  // total, kept at least one column from its neighbours so no shard is empty.
  auto boundary = [&](int k) -> std::size_t {
    if (k == 0) return 0;
    if (k == count) return ny;
    const double target = cumulative.back() * k / count;
    auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    auto b = static_cast<std::size_t>(it - cumulative.begin());
    if (b > 0 && target - cumulative[b - 1] < cumulative[b] - target) --b;  // the nearer column edge
    const auto lowest = static_cast<std::size_t>(k), highest = ny - static_cast<std::size_t>(count - k);
    return std::clamp(b, lowest, highest);
  };
  // Boundaries are monotone in k (lower_bound of rising targets, clamps rising with k).
  return {boundary(index - 1), boundary(index)};
}

std::pair<int, int> parse_shard(const std::string& text) {
  int index = 0, count = 0;
  char slash = 0, extra = 0;
  bool ok = std::sscanf(text.c_str(), "%d %c %d %c", &index, &slash, &count, &extra) == 3 && slash == '/' &&
            count >= 1 && index >= 1 && index <= count;
  RAILTAB_CHECK(ok, "--shard \"{}\": expected I/N with 1 <= I <= N, e.g. 2/8", text);
  return {index, count};
}

std::pair<int, int> parse_shard_spec(const std::string& text) {
  if (text != "auto") return parse_shard(text);
  auto read = [](const char* name, bool required) -> long {
    const char* value = std::getenv(name);
    if (value == nullptr) {
      RAILTAB_CHECK(!required, "--shard auto: ${} is not set (run it inside a Slurm job array, sbatch --array)",
                    name);
      return -1;
    }
    char* end = nullptr;
    long n = std::strtol(value, &end, 10);
    RAILTAB_CHECK(end != value && *end == '\0' && n >= 0 && n < 1000000, "--shard auto: ${}=\"{}\" is not a count",
                  name, value);
    return n;
  };
  const long id = read("SLURM_ARRAY_TASK_ID", true);
  const long tasks = read("SLURM_ARRAY_TASK_COUNT", true);
  long first = read("SLURM_ARRAY_TASK_MIN", false);
  if (first < 0) first = 0;
  const long index = id - first + 1;
  RAILTAB_CHECK(tasks >= 1 && index >= 1 && index <= tasks,
                "--shard auto: SLURM_ARRAY_TASK_ID {} with SLURM_ARRAY_TASK_MIN {} is not one of {} tasks", id, first,
                tasks);
  return {static_cast<int>(index), static_cast<int>(tasks)};
}

}  // namespace railtab
