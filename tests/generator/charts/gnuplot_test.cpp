// SPDX-License-Identifier: Apache-2.0
// gnuplot without a shell (generator/charts/gnuplot.hpp): paths quoted for gnuplot, a path with a
// quote or shell syntax draws its chart and runs nothing (issue 19).
#include "charts/gnuplot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "core/check.hpp"
#include "generator/test_tables.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

TEST(Gnuplot, QuotesPathsForGnuplot) {
  EXPECT_EQ(gnuplot_quote("out/a.png"), "'out/a.png'");
  EXPECT_EQ(gnuplot_quote("it's.png"), "'it''s.png'");
  EXPECT_EQ(gnuplot_quote("<rm x"), "'./<rm x'");    // gnuplot would run "< cmd" as a command
  EXPECT_EQ(gnuplot_quote("|cat"), "'./|cat'");      // and pipe "| cmd" output into one
  EXPECT_EQ(gnuplot_quote("/abs/<x"), "'/abs/<x'");
  EXPECT_THROW(gnuplot_quote("a\nb.png"), Error);
  EXPECT_EQ(gnuplot_text("a\"b\\c"), "a\\\"b\\\\c");
}

// Chart titles name the scene's profiles and track (its description), not only its name.
TEST(Gnuplot, SceneTitleCarriesTheDescription) {
  EXPECT_EQ(scene_title("default", "S1002 on UIC60 1:40"), "default (S1002 on UIC60 1:40)");
  EXPECT_EQ(scene_title("t", ""), "t");
}

TEST(Gnuplot, HostilePathDrawsTheChartAndRunsNothing) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  testing::TempDir base("gnuplot_hostile");
  // A quote ends the old shell string; $(...) and ; would then run as commands.
  const fs::path dir = base / "it's $(touch PWNED); touch PWNED2 '";
  fs::create_directories(dir);
  const fs::path csv = dir / "d.csv";
  std::ofstream(csv) << "0,0\n1,1\n";
  const fs::path png = dir / "c.png";
  const std::string script = "set terminal pngcairo size 200,100\nset datafile separator ','\nplot " +
                             gnuplot_quote(csv) + " using 1:2 with lines notitle\n";
  run_gnuplot(dir / "c.gp", script, png);
  EXPECT_GT(fs::file_size(png), 0u);
  EXPECT_FALSE(fs::exists("PWNED"));
  EXPECT_FALSE(fs::exists("PWNED2"));
  EXPECT_FALSE(fs::exists(dir / "PWNED"));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"c.gp", "c.png", "d.csv"}));  // no temporary left
}

TEST(Gnuplot, FailedPlotLeavesNoImage) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  testing::TempDir dir("gnuplot_fail");
  EXPECT_THROW(run_gnuplot(dir / "c.gp", "set terminal pngcairo\nthis is not gnuplot\n", dir / "c.png"), Error);
  EXPECT_FALSE(fs::exists(dir / "c.png"));
  EXPECT_EQ(dir.files(), std::vector<std::string>{"c.gp"});
}

}  // namespace
}  // namespace railtab
