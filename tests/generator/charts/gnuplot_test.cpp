// SPDX-License-Identifier: Apache-2.0
// gnuplot without a shell (generator/charts/gnuplot.hpp): paths quoted for gnuplot, a path with a
// quote or shell syntax draws its chart and runs nothing (docs/reliability.md, "Programs railtab
// starts").
#include "charts/gnuplot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/check.hpp"
#include "error_message.hpp"
#include "generator/test_tables.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;

TEST(Gnuplot, QuotesPathsForGnuplot) {
  EXPECT_EQ(gnuplot_quote("out/a.png"), "\"out/a.png\"");
  EXPECT_EQ(gnuplot_quote("it's.png"), "\"it\\047s.png\"");
  EXPECT_EQ(gnuplot_quote("<rm x"), "\"./\\074rm x\"");  // gnuplot would run "< cmd" as a command
  EXPECT_EQ(gnuplot_quote("|cat"), "\"./\\174cat\"");    // and pipe "| cmd" output into one
  EXPECT_EQ(gnuplot_quote("/abs/<x"), "\"/abs/\\074x\"");
  EXPECT_EQ(gnuplot_quote("a\nb.png"), "\"a\\012b.png\"");
  EXPECT_THROW(gnuplot_quote(std::string("a\0b.png", 7)), Error);
}

// Every character gnuplot could act on before it reads a string (backquote: a shell command; '@':
// a macro) or inside one (quotes, backslash, newline, '$') is an octal escape.
TEST(Gnuplot, StringsHoldNothingGnuplotInterprets) {
  EXPECT_EQ(gnuplot_string("x`touch p`"), "\"x\\140touch p\\140\"");
  EXPECT_EQ(gnuplot_string("a@b$c\"d'e\\f\ng"), "\"a\\100b\\044c\\042d\\047e\\134f\\012g\"");
  EXPECT_EQ(gnuplot_string("S1002 on UIC60 (1:40), y = -6.5 mm"), "\"S1002 on UIC60 (1:40), y = -6.5 mm\"");
  EXPECT_EQ(gnuplot_string("\xe2\x82\xac"), "\"\\342\\202\\254\"");  // UTF-8 bytes come back whole
  EXPECT_EQ(gnuplot_string(std::string("a\0b", 3)), "\"a b\"");
}

TEST(Gnuplot, ScriptWithBackquoteOrMacroIsRefused) {
  EXPECT_EQ(gnuplot_script_problem("set title \"x\\140\"\nplot x\n"), "");
  EXPECT_NE(gnuplot_script_problem("set title 'a'\nset title \"`id`\"\n").find("line 2"), std::string::npos);
  EXPECT_NE(gnuplot_script_problem("set title \"@x\"\n").find("'@'"), std::string::npos);
  testing::TempDir dir("gnuplot_refused");
  EXPECT_THROW(run_gnuplot(dir / "c.gp", "set terminal pngcairo\nset title \"`touch PWNED`\"\nplot x\n",
                           dir / "c.png"),
               Error);
  EXPECT_TRUE(dir.files().empty());  // refused before anything is written or run
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

// gnuplot's warnings go to the stream the command chose (the null stream with -q), never straight
// to stderr; its error message is part of the exception.
TEST(Gnuplot, MessagesAreCapturedAndRouted) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  testing::TempDir dir("gnuplot_messages");
  std::ofstream(dir / "one.csv") << "0,1\n";  // one point: gnuplot warns about the empty ranges
  std::ostringstream messages;
  set_gnuplot_messages(messages);
  run_gnuplot(dir / "c.gp",
              "set terminal pngcairo size 200,100\nset datafile separator ','\nplot " + gnuplot_quote(dir / "one.csv") +
                  " using 1:2 with lines notitle\n",
              dir / "c.png");
  set_gnuplot_messages(std::cerr);
  EXPECT_TRUE(fs::exists(dir / "c.png"));
  EXPECT_NE(messages.str().find("empty x range"), std::string::npos) << messages.str();
  const std::string error = test::error_message([&] {
    run_gnuplot(dir / "d.gp", "set terminal pngcairo\nset yrange [1:1]\nplot x\n", dir / "d.png");
  });
  EXPECT_NE(error.find("empty y range"), std::string::npos) << error;
}

}  // namespace
}  // namespace railtab
