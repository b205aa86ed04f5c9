// SPDX-License-Identifier: Apache-2.0
// The speed-against-accuracy charts (railtab chart): runs the measurement, writes its CSVs and
// draws speed_accuracy.png (time against error, Pareto fronts) and table_memory.png.
#include "speed_accuracy/speed_accuracy_chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "charts/gnuplot.hpp"
#include "core/check.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

// Points of the Pareto fronts sorted by time, two gnuplot data blocks (tread, flange).
void write_pareto(const SpeedAccuracyResult& r, const std::filesystem::path& path) {
  std::ostringstream out;
  for (int panel = 0; panel < 2; ++panel) {
    std::vector<std::pair<double, double>> pts;
    for (const SaRow& row : r.rows) {
      if (panel == 0 && row.pareto_tread) pts.emplace_back(row.time_tread_us, row.err_force_tread);
      if (panel == 1 && row.pareto_flange) pts.emplace_back(row.time_flange_us, row.err_force_flange);
    }
    std::sort(pts.begin(), pts.end());
    out << (panel == 0 ? "# tread: time_us,err_force\n" : "# flange: time_us,err_force\n");
    for (const auto& [t, e] : pts) out << fmt::format("{:.6g},{:.6g}\n", t, e);
    out << "\n\n";
  }
  write_text_file(path, out.str());
}

}  // namespace

SpeedAccuracyResult draw_speed_accuracy_charts(const Scene& scene, const std::filesystem::path& dir,
                                               SpeedAccuracyOptions so, SpeedAccuracyChartFiles& files) {
  std::filesystem::create_directories(dir);
  so.work_dir = dir / "tables";
  const SpeedAccuracyResult r = measure_speed_accuracy(scene, so);
  if (!so.keep_tables) std::filesystem::remove_all(so.work_dir);

  const std::filesystem::path csv = files.csv = dir / "speed_accuracy.csv";
  const std::filesystem::path states_csv = dir / "speed_accuracy_states.csv";
  const std::filesystem::path pareto_csv = dir / "speed_accuracy_pareto.csv";
  const std::filesystem::path mem_csv = files.memory_csv = dir / "table_memory.csv";
  write_speed_accuracy_csv(r, csv);
  write_states_csv(r, states_csv);
  write_table_memory_csv(r, mem_csv);
  write_pareto(r, pareto_csv);

  // Columns of speed_accuracy.csv (1-based): 1 label, 3 family, 9 time_tread_us, 10 time_flange_us,
  // 15 err_force_tread, 16 err_force_flange, 26 pareto_tread, 27 pareto_flange. Labels on Pareto points.
  const std::string ref_title =
      r.contact_reference ? "reference: CONTACT half-space (block C)" : "reference: " + r.reference;
  struct Family {
    const char* name;
    const char* title;
    int pt;
    const char* color;
  };
  const Family families[] = {{"hertz", "Hertz + elliptic FASTSIM (e = elements)", 7, "#1b9e77"},
                             {"linder", "Linder (strips x elements)", 9, "#d95f02"},
                             {"kik-piotrowski", "Kik-Piotrowski (strips x elements)", 11, "#7570b3"},
                             {"stripes-a", "STRIPES A (strips x elements)", 5, "#e7298a"},
                             {"stripes-ab", "STRIPES A\\&B (strips x elements)", 13, "#66a61e"},
                             {"lookup-linear", "table lookup, linear (y step)", 15, "#000000"},
                             {"lookup-cubic", "table lookup, cubic (y step)", 4, "#7f7f7f"},
                             {"halfspace", "exact half-space model (railtab)", 3, "#a6761d"},
                             {"lookup-linear-exact", "table of the exact model, linear", 6, "#a6761d"},
                             {"lookup-cubic-exact", "table of the exact model, cubic", 12, "#a6761d"}};
  auto panel = [&](int tcol, int ecol, int pcol, int block, const char* title) {
    std::string s = fmt::format("set title '{}'\nplot ", title);
    for (const Family& f : families) {
      s += fmt::format(
          "{csv} using (strcol(3) eq '{n}' ? ${t} : 1/0):{e} with points pt {pt} ps 1.3 lc rgb '{c}' title '{ti}', \\\n"
          "     {csv} using (strcol(3) eq '{n}' && ${p} == 1 ? ${t} : 1/0):{e}:1 with labels noenhanced "
          "font ',7' left offset 0.8,0.6 tc rgb '{c}' notitle, \\\n     ",
          fmt::arg("csv", gnuplot_quote(csv)), fmt::arg("n", f.name), fmt::arg("t", tcol), fmt::arg("e", ecol),
          fmt::arg("p", pcol),
          fmt::arg("pt", f.pt), fmt::arg("c", f.color), fmt::arg("ti", f.title));
    }
    s += fmt::format("{} index {} using 1:2 with steps lw 2 lc rgb '#cc0000' title 'Pareto front'\n",
                     gnuplot_quote(pareto_csv), block);
    return s;
  };
  const std::filesystem::path png = files.png = dir / "speed_accuracy.png";
  std::string script = fmt::format(R"GP(set terminal pngcairo size 1400,620 font ",10"
set datafile separator ','
set datafile missing 'nan'
set logscale xy
set grid xtics ytics mxtics mytics lw 0.5
set format y '%g'
set xlabel 'time per evaluation [us] (models: geometry + normal + FASTSIM + wear; tables: one lookup)'
set ylabel 'median |F - F_{{ref}}| / |F_{{ref}}| (creep force)'
set key bottom left font ',8' box opaque
# Labels start right of their point (left-aligned): centred ones ran past the y axis, over its tics,
# for the lookups at ~0.1 us; the x range starts below them for the same reason.
set xrange [0.03:*]
set multiplot layout 1,2 title {title} noenhanced font ',11'
)GP",
                                   fmt::arg("title", gnuplot_string(fmt::format("{}: speed against accuracy, {}\n{}",
                                                                                 scene.name, ref_title, r.setup))));
  script += panel(9, 15, 26, 0, "tread contact (dy = -6..6 mm)");
  script += "unset key\n";
  script += panel(10, 16, 27, 1, "flange contact (dy = 7..10 mm)");
  script += "unset multiplot\n";
  run_gnuplot(dir / "speed_accuracy.gp", script, png);

  // Table memory against lookup error. table_memory.csv: 1 label, 2 method, 3 y step, 4 creep grid,
  // 5 file bytes, 6 memory bytes, 7 time, 8 err_force, 10 tread, 11 flange.
  const std::filesystem::path mpng = files.memory_png = dir / "table_memory.png";
  const std::string mscript = fmt::format(R"GP(set terminal pngcairo size 900,600 font ",10"
set datafile separator ','
set datafile missing 'nan'
set logscale xy
set grid xtics ytics mxtics mytics lw 0.5
set format y '%g'
set xlabel 'table size in memory [bytes] (Table::memory_bytes; file sizes in table_memory.csv)' noenhanced
set yrange [5e-4:1]
set ylabel 'median relative creep-force error'
set key top right font ',8' box opaque
set title {title} noenhanced
plot {csv} using (strcol(2) eq 'linear' ? $6 : 1/0):10 with points ps 1.4 pt 7 lc rgb '#1b9e77' title 'linear, tread', \
     {csv} using (strcol(2) eq 'linear' ? $6 : 1/0):11 with points ps 1.4 pt 5 lc rgb '#d95f02' title 'linear, flange', \
     {csv} using (strcol(2) eq 'cubic' ? $6 : 1/0):10 with points ps 1.4 pt 6 lc rgb '#1b9e77' title 'cubic, tread', \
     {csv} using (strcol(2) eq 'cubic' ? $6 : 1/0):11 with points ps 1.4 pt 4 lc rgb '#d95f02' title 'cubic, flange', \
     {csv} using (strcol(2) eq 'linear' ? $6 : 1/0):14 with points ps 1.4 pt 9 lc rgb '#7570b3' title 'linear, interpolation only (vs direct model)', \
     {csv} using (strcol(2) eq 'linear' ? $6 : 1/0):10:(strcol(1)[8:*]) with labels font ',8' offset 0,0.8 notitle
)GP",
                                          fmt::arg("csv", gnuplot_quote(mem_csv)),
                                          fmt::arg("title", gnuplot_string(fmt::format(
                                                                "{}: table lookup error against memory, {}\n(y step; 'fine' = "
                                                                "fine creepage grid; roll 0 and load fixed)",
                                                                scene.name, ref_title))));
  run_gnuplot(dir / "table_memory.gp", mscript, mpng);

  return r;
}

}  // namespace railtab
