// Writes a gnuplot script file and runs gnuplot on it (the one place charts leave the process).
#include "charts/gnuplot.hpp"

#include <cstdlib>
#include <fstream>

#include "core/check.hpp"

namespace railtab {

void run_gnuplot(const std::filesystem::path& script_path, const std::string& script) {
  {
    std::ofstream out(script_path);
    RAILTAB_CHECK(out.good(), "cannot write gnuplot script {}", script_path.string());
    out << script;
  }
  RAILTAB_CHECK(std::system("command -v gnuplot > /dev/null 2>&1") == 0,
                "gnuplot not found: run scripts/install-deps.sh (package gnuplot-nox)");
  const std::string command = "gnuplot '" + script_path.string() + "'";
  const int rc = std::system(command.c_str());
  RAILTAB_CHECK(rc == 0, "gnuplot failed on {} (exit status {})", script_path.string(), rc);
}

}  // namespace railtab
