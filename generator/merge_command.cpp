// Placeholder until the merge subcommand lands; replaced by its owner.
#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace railtab {
void add_merge_command(CLI::App& /*app*/) {}
}  // namespace railtab
