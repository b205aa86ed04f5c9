// SPDX-License-Identifier: Apache-2.0
// railtab simulate: table, bogie run, wear post-processing and profile update, step after step.
#include "simulate/simulation_run.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "charts/wear_chart.hpp"
#include "core/check.hpp"
#include "profile/formats/profile_io.hpp"
#include "profile/standard/s1002.hpp"
#include "scene/scene.hpp"
#include "scene/toml_section.hpp"
#include "simulate/bogie_run.hpp"
#include "simulate/direct_contact_model.hpp"
#include "simulate/lookup_contact_model.hpp"
#include "simulate/worn_profile.hpp"
#include "generate/generate.hpp"
#include "table/interrupt.hpp"
#include "table/output_file.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Text to `file` through a locked, synced temporary (table/output_file.hpp): a reader never sees
// half a file, a non-regular `file` is refused.
void write_file(const fs::path& file, const std::string& text) { write_text_file(file, text); }

// The wheel profile of a scene as a Profile (the worn profile is written from it).
ProfilePtr wheel_profile(const Scene& scene) {
  if (scene.wheel.file.empty()) {
    RAILTAB_CHECK(scene.wheel.name == "s1002", "{}: unknown built-in wheel profile '{}'", scene.path.string(),
                  scene.wheel.name);
    return make_s1002_profile();
  }
  ProfileReadOptions options;
  options.smoothing_length = scene.wheel.smoothing_length;
  options.mirror_y = scene.wheel.mirror_y;
  options.mirror_z = scene.wheel.mirror_z;
  return read_profile(scene.wheel.file, ProfileKind::wheel, options);
}

// The step's contact scene: the simulation's contact scene with the current wheel profile, the
// model, the simulation speed (slip velocities for wear), the lubrication factor and, when
// `yaw_nodes` is not empty, a yaw axis at those nodes. Profile
// files are written relative to the step directory so that the directory reproduces the step
// with `railtab generate` / `railtab eval`.
std::string step_scene_text(const SimulationScene& sim, const Scene& contact, const std::string& model,
                            const std::vector<double>& yaw_nodes, const fs::path& worn_wheel,
                            const fs::path& step_dir, const std::string& name) {
  toml::table root = scene_toml::parse(scene_toml::read_text(sim.contact_scene, "contact scene"),
                                       sim.contact_scene.string());
  auto section = [&](const char* key) -> toml::table& {
    if (!root.contains(key)) root.insert(key, toml::table{});
    return *root[key].as_table();
  };
  section("scene").insert_or_assign("name", name);
  section("scene").insert_or_assign(
      "description", fmt::format("railtab simulate {}: {}", sim.path.filename().string(), name));
  toml::table& profiles = section("profiles");
  if (!worn_wheel.empty()) {
    profiles.insert_or_assign("wheel", fs::proximate(worn_wheel, step_dir).generic_string());
  } else if (!contact.wheel.file.empty()) {
    profiles.insert_or_assign("wheel", fs::proximate(fs::absolute(contact.wheel.file), step_dir).generic_string());
  }
  if (!contact.rail.file.empty()) {
    profiles.insert_or_assign("rail", fs::proximate(fs::absolute(contact.rail.file), step_dir).generic_string());
  }
  section("contact").insert_or_assign("normal_model", model);
  section("contact").insert_or_assign("speed", sim.speed);
  section("wear").insert_or_assign("lubrication_factor", sim.lubrication_factor);
  if (!yaw_nodes.empty()) {
    toml::array nodes;
    for (double v : yaw_nodes) nodes.push_back(v);
    section("grid").insert_or_assign("yaw", nodes);
  }
  std::ostringstream text;
  text << "# Written by railtab simulate from " << sim.contact_scene.generic_string() << " (step scene).\n"
       << root << "\n";
  return text.str();
}

double integrate(const std::vector<double>& u, const std::vector<double>& depth) {
  if (u.size() < 2) return 0.0;
  const double du = (u.back() - u.front()) / static_cast<double>(u.size() - 1);  // uniform bins
  double area = 0.0;
  for (double d : depth) area += d * du;
  return area;
}

nlohmann::json to_json(const RunSummary& r) {
  nlohmann::json j = {
      {"dynamics", r.label},
      {"simulated_seconds", r.simulated_seconds},
      {"distance_m", r.distance},
      {"steps", r.steps},
      {"dynamics_wall_seconds", r.dynamics_wall_seconds},
      {"wear_wall_seconds", r.wear_wall_seconds},
      {"simulated_seconds_per_wall_second",
       r.dynamics_wall_seconds > 0.0 ? r.simulated_seconds / r.dynamics_wall_seconds : 0.0},
      {"stable_time_step_estimate_s", r.stable_time_step_estimate},
      {"max_creep_force_ratio", r.max_creep_force_ratio},
      {"max_abs_y_relative_m", {{"leading", r.max_abs_y[0]}, {"trailing", r.max_abs_y[1]}}},
      {"max_abs_yaw_rad", {{"leading", r.max_abs_yaw[0]}, {"trailing", r.max_abs_yaw[1]}}},
      {"max_y_over_q", {{"leading", r.max_y_over_q[0]}, {"trailing", r.max_y_over_q[1]}}},
      {"yaw_axis", r.yaw_axis},
      {"queries", r.queries},
      {"out_of_range", r.out_of_range},
      {"invalid_input", r.invalid_input},
      {"contact_failures", r.contact_failures},
      {"wear_samples_per_wheelset", r.wear_samples},
      {"status", status::describe(r.status)},
  };
  nlohmann::json axes = nlohmann::json::object();
  for (std::size_t v = 0; v < kLookupVariables; ++v) {
    if (v != kLookupVariables - 1 || r.yaw_axis) axes[kLookupVariableNames[v]] = r.outside_axis[v];  // yaw: yaw tables only
  }
  j["outside_axis"] = axes;
  return j;
}

void log_line(const SimulationOptions& options, const std::string& line) {
  if (options.log) *options.log << line << std::endl;
}

bool is_stripes(const std::string& name) { return name.rfind("stripes", 0) == 0; }

// Where the wear sits: depth-weighted centroid, deepest bin, and the shares of the worn area on
// the flange side of the nominal running circle (u < 0) and at the flange root and flange
// (u < -25 mm).
void locate_wear(ModelSummary& ms) {
  double weight_sum = 0.0, moment = 0.0, flange_side = 0.0, flange_root = 0.0;
  for (std::size_t i = 0; i < ms.cumulative_depth.size(); ++i) {
    const double d = ms.cumulative_depth[i];
    weight_sum += d;
    moment += d * ms.u[i];
    if (ms.u[i] < 0.0) flange_side += d;
    if (ms.u[i] < kFlangeRootU) flange_root += d;
    if (d > ms.peak_depth) {
      ms.peak_depth = d;
      ms.peak_u = ms.u[i];
    }
  }
  ms.centroid_u = weight_sum > 0.0 ? moment / weight_sum : 0.0;
  ms.flange_side_share = weight_sum > 0.0 ? flange_side / weight_sum : 0.0;
  ms.flange_root_share = weight_sum > 0.0 ? flange_root / weight_sum : 0.0;
}

// One post-processor's way through the wear steps: its own worn wheel after step 0.
struct Branch {
  ModelSummary summary;
  fs::path worn_wheel;  // empty: the contact scene's wheel
  std::vector<double> cumulative;
};

// The wear post-processors of the run (the options' or the scene's), each known and listed once.
std::vector<std::string> checked_processors(const SimulationScene& sim, const SimulationOptions& options) {
  RAILTAB_CHECK(!options.out.empty(), "simulate: no output directory given");
  RAILTAB_CHECK(options.duration >= 0.0 && std::isfinite(options.duration), "simulate: --duration must be >= 0, got {}",
                options.duration);
  const std::vector<std::string> processors =
      options.post_processors.empty() ? sim.wear_post_processors : options.post_processors;
  RAILTAB_CHECK(!processors.empty(), "simulate: no wear post-processor given");
  for (const auto& p : processors) check_wear_post_processor(p);  // throws naming a bad one
  for (std::size_t i = 0; i < processors.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      RAILTAB_CHECK(processors[i] != processors[j], "simulate: wear post-processor '{}' listed twice", processors[i]);
    }
  }
  return processors;
}

// One dynamics run of a wear step: which step, under which label, where its files go.
struct StepRun {
  const SimulationScene& sim;
  const SimulationOptions& options;
  const fs::path& directory;  // OUT/<name>
  std::string label;          // "shared" (step 0) or the post-processor
  int k = 0;                  // the wear step

  [[noreturn]] void stop(const std::string& where) const {
    throw Interrupted(fmt::format("{} {} step {}: interrupted {}; the finished steps' files in {} are whole, "
                                  "summary.json is not written",
                                  sim.name, label, k, where, directory.string()));
  }
};

// The contact model of the dynamics: the step's table (generated here) or, with --direct, the
// core at every call.
struct StepContact {
  std::unique_ptr<vehicle::ContactModel> model;
  const LookupContactModel* lookup = nullptr;
  const DirectContactModel* direct = nullptr;
  double generate_seconds = 0.0;
};

StepContact step_contact(const StepRun& run, const Scene& scene, const fs::path& scene_file, const fs::path& dir) {
  StepContact c;
  if (run.options.direct) {
    auto d = std::make_unique<DirectContactModel>(scene);
    c.direct = d.get();
    c.model = std::move(d);
    return c;
  }
  GenerateOptions g;
  g.scene = scene_file;
  g.output = dir / "table.h5";
  g.threads = run.options.threads;
  g.interrupt = run.options.interrupt;
  const auto tg = Clock::now();
  SweepSummary s;
  try {
    s = generate_table(g);
  } catch (const Interrupted&) {  // its message offers --resume, which simulate has not
    run.stop(fmt::format("in the table generation ({} not written)", g.output.string()));
  }
  c.generate_seconds = seconds_since(tg);
  log_line(run.options, fmt::format("{} {} step {}: {} table {} ({} points, {} failures) in {:.1f} s", run.sim.name,
                                    run.label, run.k, run.sim.dynamics_model, g.output.string(), s.points_total,
                                    s.failures, c.generate_seconds));
  auto l = std::make_unique<LookupContactModel>(lookup::Table::load(g.output.string()));
  c.lookup = l.get();
  c.model = std::move(l);
  return c;
}

// The bogie over the route with the step's contact model, the wear post-processors fed on the way.
RunSummary run_dynamics(const StepRun& step, const Scene& scene, const StepContact& contact, const fs::path& dir,
                        WearPostProcessing& wear) {
  const SimulationScene& sim = step.sim;
  const SimulationOptions& options = step.options;
  RunSummary run;
  try {
    run = run_bogie(sim, *contact.model, contact.lookup, contact.direct, scene.tangential.friction, options.duration,
                    dir / "trajectory.csv", wear, options.interrupt);
  } catch (const Interrupted& e) {
    step.stop(fmt::format("in the dynamics ({})", e.what()));
  }
  run.label = step.label;
  log_line(options,
           fmt::format("{} {} step {}: {:.1f} s simulated ({:.0f} m) in {:.2f} s wall: {:.1f} simulated s per wall "
                       "s; max |y| {:.2f} / {:.2f} mm (leading / trailing); out of range {} of {} queries; "
                       "{} wear samples per wheelset in {:.1f} s",
                       sim.name, step.label, step.k, run.simulated_seconds, run.distance, run.dynamics_wall_seconds,
                       run.dynamics_wall_seconds > 0 ? run.simulated_seconds / run.dynamics_wall_seconds : 0.0,
                       run.max_abs_y[0] * 1e3, run.max_abs_y[1] * 1e3, run.out_of_range, run.queries,
                       run.wear_samples, run.wear_wall_seconds));
  if (run.stable_time_step_estimate > 0.0 && sim.time_step > run.stable_time_step_estimate) {
    log_line(options, fmt::format("warning: time_step {} s exceeds the stable RK4 step estimate {:.3e} s",
                                  sim.time_step, run.stable_time_step_estimate));
  }
  if (run.out_of_range > 0 || run.invalid_input > 0) {
    log_line(options, fmt::format("warning: {} table queries out of range, {} invalid (see summary.json "
                                  "outside_axis): widen the contact scene's grid",
                                  run.out_of_range, run.invalid_input));
  }
  return run;
}

// One post-processor's wear of a step, scaled to the step's running distance: each counted
// wheelset's left and right depth, and their mean (one wheel profile).
struct StepWear {
  std::vector<std::array<std::vector<double>, vehicle::kWheels>> depth;
  std::vector<double> mean;
};

// Scales post-processor j's accumulators to the step's running distance (shortened by the depth
// limit) and fills the step's distance, peak depth and wear counts.
StepWear scale_wear(const SimulationScene& sim, WearPostProcessing& wear, std::size_t j, const std::string& processor,
                    int k, double step_distance, StepSummary& step) {
  // The route stands for the step's running distance: wear scales with distance. Equal
  // left and right curves and forward-backward symmetry: one wheel profile is the mean of
  // both wheels and all counted wheelsets.
  const std::vector<double>& u = wear.accumulator(j, 0).u();
  const double weight = 1.0 / (static_cast<double>(sim.positions.size()) * vehicle::kWheels);
  const auto mean_depth = [&](double distance) {  // the accumulators' mean at `distance`
    std::vector<double> m(u.size(), 0.0);
    for (std::size_t i = 0; i < sim.positions.size(); ++i) {
      const WearAccumulator& acc = wear.accumulator(j, i);
      if (acc.distance() <= 0.0) continue;
      for (int w = 0; w < vehicle::kWheels; ++w) {
        const std::vector<double>& d = acc.depth(w);
        for (std::size_t b = 0; b < u.size(); ++b) m[b] += weight * d[b] * (distance / acc.distance());
      }
    }
    return m;
  };
  // The profile update is the smoothed mean depth (write_worn_profile). With a depth limit
  // the step ends where its largest value reaches the limit: the wear is linear in the
  // distance at fixed states, so the distance scales by limit / peak.
  const std::vector<double> nominal = smooth_depth(u, mean_depth(step_distance), sim.profile_smoothing);
  const double nominal_peak = *std::max_element(nominal.begin(), nominal.end());
  step.running_distance = step_distance;
  step.profile_peak_depth = nominal_peak;
  if (sim.step_depth_limit > 0.0 && nominal_peak > sim.step_depth_limit) {
    step.running_distance = step_distance * (sim.step_depth_limit / nominal_peak);
    step.profile_peak_depth = sim.step_depth_limit;
    step.depth_limited = true;
  }
  // A profile update deeper than this is no wear step of a wheel: the linear scaling of the
  // route's wear to the step's distance has left the physics (running_distance 1e300 gave
  // a worn profile 1e290 mm deep, written with exit 0).
  RAILTAB_CHECK(step.profile_peak_depth <= kMaxProfileUpdateDepth,
                "{}: {} step {}: the profile update would wear {:.4g} mm deep over {:.4g} km "
                "(simulation.running_distance / wear_steps), beyond {} mm for one step: raise wear_steps, "
                "lower running_distance or set step_depth_limit",
                sim.path.empty() ? sim.name : sim.path.string(), processor, k, step.profile_peak_depth * 1e3,
                step.running_distance / 1e3, kMaxProfileUpdateDepth * 1e3);
  StepWear result;
  result.mean.assign(u.size(), 0.0);
  for (std::size_t i = 0; i < sim.positions.size(); ++i) {
    WearAccumulator& acc = wear.accumulator(j, i);
    if (acc.distance() > 0.0) acc.scale(step.running_distance / acc.distance());
    step.wear_failures += acc.failures();
    step.wear_not_converged += acc.not_converged();
    step.wear_status |= acc.status_seen();
    step.wear_clipped_area += acc.clipped_area(0) + acc.clipped_area(1);
    result.depth.push_back({acc.depth(0), acc.depth(1)});
    for (const auto& d : result.depth.back()) {
      for (std::size_t b = 0; b < u.size(); ++b) result.mean[b] += weight * d[b];
    }
  }
  return result;
}

// wear.csv (depth per wheel and position, mean, cumulative) and worn_area.csv of one step.
void write_wear_csv(const SimulationScene& sim, const fs::path& wear_dir, const std::vector<double>& u,
                    const StepWear& w, const std::vector<double>& cumulative, const StepSummary& step) {
  std::ostringstream csv;
  csv << "u_m";
  for (const std::string& position : sim.positions) {
    csv << ",depth_left_" << position << "_m,depth_right_" << position << "_m";
  }
  csv << ",depth_mean_m,depth_cumulative_m\n";
  for (std::size_t b = 0; b < u.size(); ++b) {
    csv << fmt::format("{:.6f}", u[b]);
    for (const auto& d : w.depth) csv << fmt::format(",{:.6e},{:.6e}", d[0][b], d[1][b]);
    csv << fmt::format(",{:.6e},{:.6e}\n", w.mean[b], cumulative[b]);
  }
  write_file(wear_dir / "wear.csv", csv.str());
  write_file(wear_dir / "worn_area.csv",
             fmt::format("step,running_distance_m,worn_area_m2,worn_area_mm2,cumulative_worn_area_mm2\n"
                         "{},{},{:.6e},{:.6f},{:.6f}\n",
                         step.step, step.running_distance, step.worn_area, step.worn_area * 1e6,
                         step.cumulative_worn_area * 1e6));
}

// Post-processor j of a step's group: its wear scaled to the step, the CSVs, and the worn wheel
// (smoothed) that its next step runs on.
void wear_step(const StepRun& run, const Scene& scene, WearPostProcessing& wear, std::size_t j,
               const std::string& processor, Branch& branch, const RunSummary& dynamics, double generate_seconds,
               double step_distance) {
  const SimulationScene& sim = run.sim;
  const int k = run.k;
  StepSummary step;
  step.step = k;
  step.generate_seconds = generate_seconds;
  step.runs.push_back(dynamics);
  const std::vector<double>& u = wear.accumulator(j, 0).u();
  const StepWear w = scale_wear(sim, wear, j, processor, k, step_distance, step);
  std::vector<double>& cumulative = branch.cumulative;
  if (cumulative.empty()) cumulative.assign(u.size(), 0.0);
  for (std::size_t b = 0; b < u.size(); ++b) cumulative[b] += w.mean[b];
  step.worn_area = integrate(u, w.mean);
  step.cumulative_worn_area = integrate(u, cumulative);

  const fs::path wear_dir = run.directory / processor / fmt::format("step{}", k);
  fs::create_directories(wear_dir);
  write_wear_csv(sim, wear_dir, u, w, cumulative, step);

  // The next step runs on this post-processor's worn wheel (smoothed).
  const fs::path next = run.directory / processor / fmt::format("step{}", k + 1) / "wheel_worn.txt";
  fs::create_directories(next.parent_path());
  write_worn_profile(*wheel_profile(scene), u, w.mean, sim.profile_smoothing, next);
  branch.worn_wheel = next;
  branch.summary.running_distance += step.running_distance;
  log_line(run.options, fmt::format("{} {} step {}: worn area {:.4f} mm2 over {:.0f} km{} (cumulative {:.4f} mm2 "
                                    "after {:.0f} km); profile update peak {:.1f} um",
                                    sim.name, processor, k, step.worn_area * 1e6, step.running_distance / 1e3,
                                    step.depth_limited ? " (depth-limited)" : "", step.cumulative_worn_area * 1e6,
                                    branch.summary.running_distance / 1e3, step.profile_peak_depth * 1e6));
  branch.summary.step_cumulative_depth.push_back(cumulative);
  branch.summary.steps.push_back(std::move(step));
  branch.summary.u = u;
}

// summary.json: the scene, every dynamics run and every post-processor's steps and wear location.
nlohmann::json summary_json(const SimulationScene& sim, const SimulationOptions& options,
                            const SimulationSummary& summary) {
  nlohmann::json j;
  j["scene"] = sim.name;
  j["contact_scene"] = sim.contact_scene.generic_string();
  j["contact"] = options.direct ? "direct (geometry + normal model + FASTSIM every evaluation)" : "table lookup";
  j["dynamics_model"] = sim.dynamics_model;
  if (!options.yaw_nodes.empty()) j["yaw_nodes_rad"] = options.yaw_nodes;  // --yaw-nodes: the tables' yaw axis
  j["vehicle"] = "bogie (two wheelsets, frame, quasi-static car body): docs/vehicle-model.md";
  j["positions"] = sim.positions;
  j["speed_m_per_s"] = sim.speed;
  j["time_step_s"] = sim.time_step;
  j["route_length_m"] = sim.route_length();
  j["running_distance_m"] = sim.running_distance;
  j["wear_steps"] = sim.wear_steps;
  j["step_depth_limit_m"] = sim.step_depth_limit;
  j["halfspace_sample_every"] = sim.halfspace_sample_every;
  j["lubrication_factor"] = sim.lubrication_factor;
  j["wear_scaling"] = "depth x (running distance per step / route distance sampled)";
  j["simulated_seconds_per_wall_second"] = simulation_speed(summary);
  for (const RunSummary& r : summary.runs) j["runs"].push_back(to_json(r));
  for (const ModelSummary& m : summary.models) {
    nlohmann::json jm;
    jm["post_processor"] = m.model;
    for (const StepSummary& s : m.steps) {
      nlohmann::json js = {{"step", s.step},
                           {"running_distance_m", s.running_distance},
                           {"profile_peak_depth_m", s.profile_peak_depth},
                           {"depth_limited", s.depth_limited},
                           {"worn_area_m2", s.worn_area},
                           {"worn_area_mm2", s.worn_area * 1e6},
                           {"cumulative_worn_area_mm2", s.cumulative_worn_area * 1e6},
                           {"generate_seconds", s.generate_seconds},
                           {"dynamics", s.runs.empty() ? "" : s.runs.front().label},
                           {"wear_failures", s.wear_failures},
                           {"wear_not_converged", s.wear_not_converged},
                           {"wear_status", status::describe(s.wear_status)},
                           {"wear_clipped_area_m2", s.wear_clipped_area}};
      jm["steps"].push_back(js);
    }
    const double total = m.steps.empty() ? 0.0 : m.steps.back().cumulative_worn_area;
    jm["running_distance_m"] = m.running_distance;
    jm["total_worn_area_m2"] = total;
    jm["total_worn_area_mm2"] = total * 1e6;
    jm["wear_centroid_u_m"] = m.centroid_u;
    jm["flange_side_share"] = m.flange_side_share;
    jm["flange_root_share"] = m.flange_root_share;
    jm["peak_depth_m"] = m.peak_depth;
    jm["peak_depth_u_m"] = m.peak_u;
    j["post_processors"].push_back(jm);
  }
  return j;
}

// The chart of the cumulative radial wear (Enblom and Berg 2008 Figs. 11-13) and its evolution: every
// post-processor after each wear step. A chart that fails is a warning: the CSVs are written.
void draw_charts(const SimulationScene& sim, const SimulationOptions& options, const SimulationSummary& summary,
                 const std::vector<WearSeries>& final_series, double step_distance) {
  try {
    draw_wear_chart(final_series, summary.directory / "wear.png",
                    sim.step_depth_limit > 0.0
                        ? fmt::format("{}: radial wear after {} depth-limited steps ({} dynamics)", sim.name,
                                      sim.wear_steps, sim.dynamics_model)
                        : fmt::format("{}: radial wear after {:.0f} km ({} dynamics)", sim.name,
                                      sim.running_distance / 1e3, sim.dynamics_model));
    for (int k = 0; k + 1 < sim.wear_steps; ++k) {
      std::vector<WearSeries> series;
      for (const ModelSummary& m : summary.models) {
        series.push_back({m.model, m.u, m.step_cumulative_depth[static_cast<std::size_t>(k)], is_stripes(m.model)});
      }
      draw_wear_chart(series, summary.directory / fmt::format("wear_step{}.png", k),
                      sim.step_depth_limit > 0.0
                          ? fmt::format("{}: radial wear after depth-limited step {}", sim.name, k)
                          : fmt::format("{}: radial wear after {:.0f} km", sim.name, step_distance * (k + 1) / 1e3));
    }
  } catch (const Error& e) {
    log_line(options, fmt::format("warning: no chart: {}", e.what()));  // the CSVs are written
  }
}

}  // namespace

double simulation_speed(const SimulationSummary& summary) {
  double simulated = 0.0, wall = 0.0;
  for (const RunSummary& r : summary.runs) {
    simulated += r.simulated_seconds;
    wall += r.dynamics_wall_seconds;
  }
  return wall > 0.0 ? simulated / wall : 0.0;
}

SimulationSummary run_simulation(const SimulationScene& sim, const SimulationOptions& options) {
  const std::vector<std::string> processors = checked_processors(sim, options);
  const Scene contact = load_scene(sim.contact_scene);
  // The wheelsets have no roll degree of freedom: their roll is the kinematic one at every y.
  RAILTAB_CHECK(contact.equilibrium_roll, "{}: the contact scene of a simulation needs [grid] equilibrium_roll = true",
                sim.contact_scene.string());

  SimulationSummary summary;
  summary.name = sim.name;
  summary.directory = options.out / sim.name;
  summary.dynamics_model = sim.dynamics_model;
  fs::create_directories(summary.directory);
  // summary.json is written last: a previous run's must not sit beside this run's new step files
  // if this one is interrupted or fails.
  if (fs::remove(summary.directory / "summary.json")) {
    log_line(options, fmt::format("{}: removed the previous run's summary.json (rewritten at the end)",
                                  summary.directory.string()));
  }
  const double step_distance = sim.running_distance / sim.wear_steps;
  std::vector<Branch> branches(processors.size());
  for (std::size_t p = 0; p < processors.size(); ++p) branches[p].summary.model = processors[p];

  for (int k = 0; k < sim.wear_steps; ++k) {
    // Step 0: every post-processor starts from the same wheel, so ONE dynamics run feeds them
    // all. Later steps: each runs on its own worn wheel (its own profile evolution, as Enblom and Berg 2008
    // ran one loop per wear model).
    std::vector<std::vector<std::size_t>> groups;
    if (k == 0) {
      groups.emplace_back();
      for (std::size_t p = 0; p < processors.size(); ++p) groups.back().push_back(p);
    } else {
      for (std::size_t p = 0; p < processors.size(); ++p) groups.push_back({p});
    }
    for (const std::vector<std::size_t>& group : groups) {
      const StepRun step{sim, options, summary.directory, k == 0 ? "shared" : processors[group.front()], k};
      if (options.interrupt && options.interrupt->load()) step.stop("before the step");
      const fs::path dir = summary.directory / step.label / fmt::format("step{}", k);
      fs::create_directories(dir);
      const std::string name = fmt::format("{}-{}-step{}", sim.name, step.label, k);
      const fs::path scene_file = dir / "scene.toml";
      write_file(scene_file,
                 step_scene_text(sim, contact, sim.dynamics_model, options.yaw_nodes, branches[group.front()].worn_wheel,
                                 dir, name));
      const Scene scene = load_scene(scene_file);
      const StepContact contact_model = step_contact(step, scene, scene_file, dir);

      std::vector<std::string> names;
      for (std::size_t p : group) names.push_back(processors[p]);
      WearPostProcessing wear(scene, names, sim.positions, WearGrid{}, sim.halfspace_sample_every);
      const RunSummary run = run_dynamics(step, scene, contact_model, dir, wear);
      summary.runs.push_back(run);
      for (std::size_t j = 0; j < group.size(); ++j) {
        wear_step(step, scene, wear, j, processors[group[j]], branches[group[j]], run, contact_model.generate_seconds,
                  step_distance);
      }
    }
  }

  std::vector<WearSeries> final_series;
  for (Branch& branch : branches) {
    ModelSummary& ms = branch.summary;
    ms.cumulative_depth = branch.cumulative;
    locate_wear(ms);
    final_series.push_back({ms.model, ms.u, ms.cumulative_depth, is_stripes(ms.model)});
    summary.models.push_back(std::move(ms));
  }
  write_file(summary.directory / "summary.json", summary_json(sim, options, summary).dump(2) + "\n");
  draw_charts(sim, options, summary, final_series, step_distance);
  return summary;
}

}  // namespace railtab
