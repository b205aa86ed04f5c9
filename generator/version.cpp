#include "version.hpp"

namespace railtab {
const char* version_string() { return RAILTAB_VERSION; }
const char* git_commit() { return RAILTAB_GIT_COMMIT; }
}  // namespace railtab
