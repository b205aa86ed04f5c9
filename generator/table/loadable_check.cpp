// SPDX-License-Identifier: Apache-2.0
// The lookup's own loader run on a table file (loadable_check.hpp).
#include "table/loadable_check.hpp"

#include <fmt/format.h>

#include <railtab/lookup.hpp>

#include "core/check.hpp"

namespace railtab {

std::optional<std::string> lookup_refusal(const std::filesystem::path& path, bool shard) {
  lookup::LoadOptions options;
  options.require_checksums = true;
  options.accept_shard = shard;
  try {
    (void)lookup::Table::load(path.string(), options);
  } catch (const lookup::LoadError& e) {
    std::string problem = e.what();
    const std::string prefix = "railtab lookup: cannot load table '" + e.path() + "': ";
    if (problem.rfind(prefix, 0) == 0) problem.erase(0, prefix.size());
    return problem;
  }
  return std::nullopt;
}

void check_loadable(const std::filesystem::path& written, const std::filesystem::path& target, bool shard) {
  if (const auto problem = lookup_refusal(written, shard)) {
    throw Error(fmt::format("{}: not written: the lookup would refuse this table ({}); nothing was replaced",
                            target.string(), *problem));
  }
}

}  // namespace railtab
