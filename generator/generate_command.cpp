// Placeholder until the generate subcommand lands; replaced by its owner.
#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace railtab {
void add_generate_command(CLI::App& /*app*/) {}
}  // namespace railtab
