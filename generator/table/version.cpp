// SPDX-License-Identifier: Apache-2.0
// Version string and git commit of this build (the commit header is generated at build time).
#include "table/version.hpp"

#include "railtab_commit.h"  // generated at build time (cmake/WriteCommit.cmake)

namespace railtab {
const char* version_string() { return RAILTAB_VERSION; }
const char* git_commit() { return RAILTAB_GIT_COMMIT; }
}  // namespace railtab
