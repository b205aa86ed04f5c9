// SPDX-License-Identifier: Apache-2.0
// Version and provenance of this build, recorded in every table file.
#pragma once

namespace railtab {
const char* version_string();  // e.g. "0.1.0"
const char* git_commit();      // short commit hash of the build, or "unknown"
}  // namespace railtab
