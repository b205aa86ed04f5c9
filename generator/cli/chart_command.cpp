// railtab chart-*: charts made by the project's own commands, each from a CSV it writes first.
//   chart-geometry: rolling radius difference and contact angles against y (flange jump visible).
//   chart-pressure: pressure along the strip centre lines of every normal model (seed 000).
//   chart-stability: which status flags each normal model raises across y (stability_chart.hpp).
//   chart: speed against accuracy of every contact model setting and of table lookup
//          (speed_accuracy.hpp; docs/speed-vs-accuracy.md).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "charts/gnuplot.hpp"
#include "charts/pressure_chart.hpp"
#include "charts/speed_accuracy.hpp"
#include "charts/stability_chart.hpp"
#include "cli/commands.hpp"
#include "core/check.hpp"
#include "scene/scene.hpp"

namespace railtab {
namespace {

struct GeometryChartOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  std::string out_dir = "out";                     // output directory
  double y_min = -0.010;                           // [m]
  double y_max = 0.010;                            // [m]
  double y_step = 0.05e-3;                         // [m]
};

void run_geometry_chart(const GeometryChartOptions& opt) {
  RAILTAB_CHECK(opt.y_step > 0.0 && opt.y_max > opt.y_min, "chart-geometry: need y-min < y-max and step > 0");
  const Scene scene = load_scene(opt.scene_path);
  const ContactGeometrySolver solver = make_geometry_solver(scene);
  const std::filesystem::path dir(opt.out_dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path csv = dir / "geometry_sweep.csv";
  std::ofstream out(csv);
  RAILTAB_CHECK(out.good(), "cannot write {}", csv.string());
  out << "y_m,roll_rad,rolling_radius_difference_m,left_contact_angle_rad,right_contact_angle_rad,"
         "left_rolling_radius_m,right_rolling_radius_m,left_contacts,right_contacts\n";
  const int n = static_cast<int>(std::lround((opt.y_max - opt.y_min) / opt.y_step));
  for (int i = 0; i <= n; ++i) {
    const double y = opt.y_min + i * opt.y_step;
    const double roll = scene.equilibrium_roll ? solver.equilibrium_roll(y) : 0.0;
    const WheelsetContactGeometry g = solver.solve({y, roll});
    const ContactPoint& left = g.wheels[0].points.front();
    const ContactPoint& right = g.wheels[1].points.front();
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{}\n", y, roll,
                       g.rolling_radius_difference, left.contact_angle, right.contact_angle,
                       left.rolling_radius, right.rolling_radius, g.wheels[0].points.size(),
                       g.wheels[1].points.size());
  }
  out.close();
  const std::filesystem::path png = dir / "geometry.png";
  const std::string script = fmt::format(R"(set terminal pngcairo noenhanced size 1000,800 font ",11"
set output '{png}'
set datafile separator ','
set multiplot layout 2,1 title "{title}: rigid contact geometry, roll {roll}"
set grid
set xlabel 'wheelset lateral displacement y [mm] (+ left)'
set ylabel 'r_left - r_right [mm]'
plot '{csv}' every ::1 using ($1*1e3):($3*1e3) with lines lw 2 title 'rolling radius difference'
set ylabel 'contact angle [deg]'
plot '{csv}' every ::1 using ($1*1e3):($4*180/pi) with lines lw 2 title 'left wheel', \
     '{csv}' every ::1 using ($1*1e3):($5*180/pi) with lines lw 2 title 'right wheel'
unset multiplot
)",
                                         fmt::arg("png", png.string()), fmt::arg("csv", csv.string()),
                                         fmt::arg("title", scene.name),
                                         fmt::arg("roll", scene.equilibrium_roll ? "at kinematic equilibrium" : "0"));
  run_gnuplot(dir / "geometry.gp", script);
  std::cout << fmt::format("chart-geometry: wrote {} and {}\n", csv.string(), png.string());
}


struct SpeedChartOptions {
  std::string scene_path = "tables/default.toml";  // scene file
  std::string out_dir = "out";                     // output directory
  std::string reference;                           // block C CSV; default <source>/../shared/...
  int repeats = 11;                                // timed runs per state and model
  bool quick = false;                              // fewer settings (smoke runs)
  bool keep_tables = false;                        // keep the generated .h5 tables
};

// Points of the Pareto fronts sorted by time, two gnuplot data blocks (tread, flange).
void write_pareto(const SpeedAccuracyResult& r, const std::filesystem::path& path) {
  std::ofstream out(path);
  RAILTAB_CHECK(out.good(), "cannot write {}", path.string());
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
}

void run_speed_chart(const SpeedChartOptions& opt) {
  const Scene scene = load_scene(opt.scene_path);
  const std::filesystem::path dir(opt.out_dir);
  std::filesystem::create_directories(dir);
  SpeedAccuracyOptions so;
  so.reference_csv = opt.reference.empty()
                         ? std::filesystem::path(RAILTAB_SOURCE_DIR) / ".." / "shared" / "reference" /
                               "blockC_sweep_integer_dy.csv"
                         : std::filesystem::path(opt.reference);
  so.work_dir = dir / "tables";
  so.keep_tables = opt.keep_tables;
  so.repeats = opt.repeats;
  if (opt.quick) {
    so.models = {{NormalModel::hertz, 0, 20}, {NormalModel::linder, 50, 20}, {NormalModel::kik_piotrowski, 50, 20},
                 {NormalModel::stripes_a, 25, 20}, {NormalModel::stripes_ab, 25, 20}, {NormalModel::stripes_ab, 50, 20}};
    so.tables = {{1e-3, false}, {0.5e-3, false}};
  }
  const SpeedAccuracyResult r = measure_speed_accuracy(scene, so);
  if (!opt.keep_tables) std::filesystem::remove_all(so.work_dir);

  const std::filesystem::path csv = dir / "speed_accuracy.csv";
  const std::filesystem::path states_csv = dir / "speed_accuracy_states.csv";
  const std::filesystem::path pareto_csv = dir / "speed_accuracy_pareto.csv";
  const std::filesystem::path mem_csv = dir / "table_memory.csv";
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
                             {"lookup-cubic", "table lookup, cubic (y step)", 4, "#7f7f7f"}};
  auto panel = [&](int tcol, int ecol, int pcol, int block, const char* title) {
    std::string s = fmt::format("set title '{}'\nplot ", title);
    for (const Family& f : families) {
      s += fmt::format(
          "'{csv}' using (strcol(3) eq '{n}' ? ${t} : 1/0):{e} with points pt {pt} ps 1.3 lc rgb '{c}' title '{ti}', \\\n"
          "     '{csv}' using (strcol(3) eq '{n}' && ${p} == 1 ? ${t} : 1/0):{e}:1 with labels noenhanced "
          "font ',7' offset 0,0.8 tc rgb '{c}' notitle, \\\n     ",
          fmt::arg("csv", csv.string()), fmt::arg("n", f.name), fmt::arg("t", tcol), fmt::arg("e", ecol),
          fmt::arg("p", pcol),
          fmt::arg("pt", f.pt), fmt::arg("c", f.color), fmt::arg("ti", f.title));
    }
    s += fmt::format("'{}' index {} using 1:2 with steps lw 2 lc rgb '#cc0000' title 'Pareto front'\n",
                     pareto_csv.string(), block);
    return s;
  };
  const std::filesystem::path png = dir / "speed_accuracy.png";
  std::string script = fmt::format(R"GP(set terminal pngcairo size 1400,620 font ",10"
set output '{png}'
set datafile separator ','
set datafile missing 'nan'
set logscale xy
set grid xtics ytics mxtics mytics lw 0.5
set format y '%g'
set xlabel 'time per evaluation [us] (models: geometry + normal + FASTSIM + wear; tables: one lookup)'
set ylabel 'median |F - F_{{ref}}| / |F_{{ref}}| (creep force)'
set key bottom left font ',8' box opaque
set multiplot layout 1,2 title "{scene}: speed against accuracy, {ref}\n{setup}" font ',11'
)GP",
                                   fmt::arg("png", png.string()), fmt::arg("scene", scene.name),
                                   fmt::arg("ref", ref_title), fmt::arg("setup", r.setup));
  script += panel(9, 15, 26, 0, "tread contact (dy = -6..6 mm)");
  script += "unset key\n";
  script += panel(10, 16, 27, 1, "flange contact (dy = 7..10 mm)");
  script += "unset multiplot\n";
  run_gnuplot(dir / "speed_accuracy.gp", script);

  // Table memory against lookup error. table_memory.csv: 1 label, 2 method, 3 y step, 4 creep grid,
  // 5 file bytes, 6 memory bytes, 7 time, 8 err_force, 10 tread, 11 flange.
  const std::filesystem::path mpng = dir / "table_memory.png";
  const std::string mscript = fmt::format(R"GP(set terminal pngcairo size 900,600 font ",10"
set output '{png}'
set datafile separator ','
set datafile missing 'nan'
set logscale xy
set grid xtics ytics mxtics mytics lw 0.5
set format y '%g'
set xlabel 'table size in memory [bytes] (Table::memory_bytes; file sizes in table_memory.csv)' noenhanced
set yrange [5e-4:1]
set ylabel 'median relative creep-force error'
set key top right font ',8' box opaque
set title "{scene}: table lookup error against memory, {ref}\n(y step; 'fine' = fine creepage grid; roll 0 and load fixed)"
plot '{csv}' using (strcol(2) eq 'linear' ? $6 : 1/0):10 with points ps 1.4 pt 7 lc rgb '#1b9e77' title 'linear, tread', \
     '{csv}' using (strcol(2) eq 'linear' ? $6 : 1/0):11 with points ps 1.4 pt 5 lc rgb '#d95f02' title 'linear, flange', \
     '{csv}' using (strcol(2) eq 'cubic' ? $6 : 1/0):10 with points ps 1.4 pt 6 lc rgb '#1b9e77' title 'cubic, tread', \
     '{csv}' using (strcol(2) eq 'cubic' ? $6 : 1/0):11 with points ps 1.4 pt 4 lc rgb '#d95f02' title 'cubic, flange', \
     '{csv}' using (strcol(2) eq 'linear' ? $6 : 1/0):14 with points ps 1.4 pt 9 lc rgb '#7570b3' title 'linear, interpolation only (vs direct model)', \
     '{csv}' using (strcol(2) eq 'linear' ? $6 : 1/0):10:(sprintf('%gmm%s', $3, strcol(4) eq 'fine' ? ' fine' : '')) with labels font ',8' offset 0,0.8 notitle
)GP",
                                          fmt::arg("png", mpng.string()), fmt::arg("csv", mem_csv.string()),
                                          fmt::arg("scene", scene.name), fmt::arg("ref", ref_title));
  run_gnuplot(dir / "table_memory.gp", mscript);

  std::cout << fmt::format("chart: {} states, {}; {}\n", r.states.size(), r.reference, r.setup);
  std::cout << fmt::format("{:<32} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8} {:>10}\n", "setting", "t_tread", "t_flange",
                           "t_all", "e_tread", "e_flange", "e_all", "mem [B]");
  for (const SaRow& row : r.rows) {
    std::cout << fmt::format("{:<32} {:>8.2f}u {:>8.2f}u {:>8.2f}u {:>7.1f}% {:>7.1f}% {:>7.1f}% {:>10}{}\n",
                             row.label, row.time_tread_us, row.time_flange_us, row.time_us, row.err_force_tread * 100,
                             row.err_force_flange * 100, row.err_force * 100,
                             row.kind == "lookup" ? std::to_string(row.memory_bytes) : std::string("-"),
                             row.pareto_tread || row.pareto_flange ? "  *Pareto" : "");
  }
  std::cout << fmt::format("chart: wrote {}, {}, {}, {} in {:.1f} s\n", csv.string(), png.string(), mem_csv.string(),
                           mpng.string(), r.seconds);
}

// The options every chart command shares: the scene and the output directory.
void add_scene_and_out(CLI::App* cmd, std::string& scene_path, std::string& out_dir) {
  cmd->add_option("--scene", scene_path, "Scene file (TOML)")->capture_default_str();
  cmd->add_option("--out", out_dir, "Output directory")->capture_default_str();
}

// A y sweep: first, last and step [m].
void add_y_range(CLI::App* cmd, double& y_min, double& y_max, double& y_step) {
  cmd->add_option("--y-min", y_min, "First lateral displacement [m]")->capture_default_str();
  cmd->add_option("--y-max", y_max, "Last lateral displacement [m]")->capture_default_str();
  cmd->add_option("--y-step", y_step, "Step [m]")->capture_default_str();
}

}  // namespace

void add_chart_commands(CLI::App& app) {
  auto geo = std::make_shared<GeometryChartOptions>();
  CLI::App* cmd = app.add_subcommand(
      "chart-geometry", "Chart rolling radius difference and contact angle against y (CSV + PNG)");
  add_scene_and_out(cmd, geo->scene_path, geo->out_dir);
  add_y_range(cmd, geo->y_min, geo->y_max, geo->y_step);
  cmd->callback([geo] { run_geometry_chart(*geo); });

  struct StabilityChartOptions {
    std::string scene_path = "tables/default.toml";  // scene file
    std::string out_dir = "out";                     // output directory
    StabilityMapOptions map;                         // y range and step [m]
  };
  auto st = std::make_shared<StabilityChartOptions>();
  CLI::App* stab = app.add_subcommand(
      "chart-stability", "Chart the status flags of every normal model across y (CSV + PNG)");
  add_scene_and_out(stab, st->scene_path, st->out_dir);
  add_y_range(stab, st->map.y_min, st->map.y_max, st->map.y_step);
  stab->callback([st] {
    draw_stability_chart(load_scene(st->scene_path), st->out_dir, st->map);
    std::cout << fmt::format("chart-stability: wrote {}/stability_map.csv and stability_map.png\n", st->out_dir);
  });

  struct PressureCommandOptions {
    std::string scene_path = "tables/default.toml";  // scene file
    std::string out_dir = "out";                     // output directory
    std::string side = "right";                      // wheel
    PressureChartOptions chart;
  };
  auto pr = std::make_shared<PressureCommandOptions>();
  CLI::App* pres = app.add_subcommand(
      "chart-pressure", "Chart the pressure along the strip centre lines of every normal model (CSV + PNG)");
  add_scene_and_out(pres, pr->scene_path, pr->out_dir);
  pres->add_option("--y", pr->chart.y, "Wheelset lateral displacement [m]")->capture_default_str();
  pres->add_option("--load", pr->chart.load, "Vertical wheel load [N]")->capture_default_str();
  pres->add_option("--wheel", pr->side, "left|right")->check(CLI::IsMember({"left", "right"}))->capture_default_str();
  pres->add_option("--reference-pmax", pr->chart.reference_max_pressure,
                   "Half-space maximum pressure to draw as a line [Pa] (e.g. CONTACT block A: 888e6)");
  pres->callback([pr] {
    pr->chart.side = pr->side == "left" ? Side::left : Side::right;
    draw_pressure_chart(load_scene(pr->scene_path), pr->out_dir, pr->chart);
    std::cout << fmt::format("chart-pressure: wrote {}/pressure.csv and pressure.png\n", pr->out_dir);
  });

  auto sa = std::make_shared<SpeedChartOptions>();
  CLI::App* chart = app.add_subcommand(
      "chart", "Speed against accuracy of every contact model and of table lookup (CSV + PNG charts)");
  add_scene_and_out(chart, sa->scene_path, sa->out_dir);
  chart->add_option("--reference", sa->reference,
                    "CONTACT block C CSV (default: <source>/../shared/reference/blockC_sweep_integer_dy.csv; "
                    "absent: finest STRIPES as reference)");
  chart->add_option("--repeats", sa->repeats, "Timed runs per state and model setting")->capture_default_str();
  chart->add_flag("--quick", sa->quick, "Few settings only (smoke run)");
  chart->add_flag("--keep-tables", sa->keep_tables, "Keep the generated tables in OUT/tables");
  chart->callback([sa] { run_speed_chart(*sa); });
}

}  // namespace railtab
