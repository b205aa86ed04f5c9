// Placeholder until the inspect subcommand lands; replaced by its owner.
#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace railtab {
void add_inspect_command(CLI::App& /*app*/) {}
}  // namespace railtab
