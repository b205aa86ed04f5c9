// Placeholder until the chart subcommands land; replaced by its owner.
#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace railtab {
void add_chart_commands(CLI::App& /*app*/) {}
}  // namespace railtab
