// SPDX-License-Identifier: Apache-2.0
// Loading a table file into the query layout (table_data.hpp).
#pragma once

#include <memory>
#include <string>

#include "table_data.hpp"

namespace railtab::lookup::detail {

// Reads and checks the whole file against docs/table-format.md. Throws LoadError.
std::shared_ptr<TableData> load_table_data(const std::string& path, const LoadOptions& options);

}  // namespace railtab::lookup::detail
