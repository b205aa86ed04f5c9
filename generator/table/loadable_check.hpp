// SPDX-License-Identifier: Apache-2.0
// The lookup's own loader (railtab::lookup::Table::load) as a check for the generator: a table
// just written is loaded before it replaces its target, and merge loads each shard before it
// joins them, so railtab never reports success for a table a simulation would refuse
// (docs/reliability.md, "Files railtab writes").
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace railtab {

// Why the lookup refuses the table file `path` (its problem, without the path), or nothing when
// it loads. A shard is loaded as the table of its own y range; checksums are required (railtab
// writes them into every table).
std::optional<std::string> lookup_refusal(const std::filesystem::path& path, bool shard);

// Throws railtab::Error naming `target` and the problem when the lookup refuses `written` (the
// temporary about to become `target`).
void check_loadable(const std::filesystem::path& written, const std::filesystem::path& target, bool shard);

}  // namespace railtab
