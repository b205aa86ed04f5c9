// Placeholder until the eval subcommand lands; replaced by its owner.
#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace railtab {
void add_eval_command(CLI::App& /*app*/) {}
}  // namespace railtab
