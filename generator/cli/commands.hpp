// SPDX-License-Identifier: Apache-2.0
// Subcommands of the railtab program; each lives in its own file and registers itself here.
#pragma once

namespace CLI {
class App;
}

namespace railtab {
void add_eval_command(CLI::App& app);      // eval_command.cpp: one state of a scene
void add_generate_command(CLI::App& app);  // generate_command.cpp: the table sweep
void add_inspect_command(CLI::App& app);   // inspect_command.cpp: summary of a table file
void add_query_command(CLI::App& app);     // query_command.cpp: interpolate a table (lookup)
void add_merge_command(CLI::App& app);     // merge_command.cpp: join shards into one table
void add_chart_commands(CLI::App& app);    // chart_command.cpp: PNG charts from CSV
void add_conicity_command(CLI::App& app);  // conicity_command.cpp: equivalent conicity (EN 15302)
void add_simulate_command(CLI::App& app);  // simulate_command.cpp: bogie run with wear
void add_export_command(CLI::App& app);    // export_command.cpp: a table's creep forces as CSV
}  // namespace railtab
