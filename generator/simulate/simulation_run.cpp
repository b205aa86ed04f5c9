// railtab simulate: table, wheelset run, wear accumulation and profile update, step after step.
#include "simulate/simulation_run.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

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
#include "profile/profile_io.hpp"
#include "profile/s1002.hpp"
#include "scene/scene.hpp"
#include "simulate/direct_contact_model.hpp"
#include "simulate/lookup_contact_model.hpp"
#include "simulate/wear_accumulator.hpp"
#include "simulate/worn_profile.hpp"
#include "sweep/generate.hpp"
#include "table/output_file.hpp"
#include "vehicle/wheelset_model.hpp"

namespace railtab {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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
  return read_profile(scene.wheel.file, ProfileKind::wheel, scene.wheel.smoothing_length);
}

// The step's contact scene: the simulation's contact scene with the current wheel profile, the
// model, the simulation speed (slip velocities for wear) and the lubrication factor. Profile
// files are written relative to the step directory so that the directory reproduces the step
// with `railtab generate` / `railtab eval`.
std::string step_scene_text(const SimulationScene& sim, const Scene& contact, const std::string& model,
                            const fs::path& worn_wheel, const fs::path& step_dir, const std::string& name) {
  toml::table root = toml::parse_file(sim.contact_scene.string());
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
  std::ostringstream text;
  text << "# Written by railtab simulate from " << sim.contact_scene.generic_string() << " (step scene).\n"
       << root << "\n";
  return text.str();
}

double slot_force_ratio(const vehicle::ContactSnapshot& snap, double mu) {
  double worst = 0.0;
  for (int w = 0; w < vehicle::kWheels; ++w) {
    for (int s = 0; s < vehicle::kContactSlots; ++s) {
      const vehicle::SlotContact& c = snap.contacts[w].slot[s];
      if (!c.loaded) continue;
      const double f = std::hypot(snap.forces[w][s].fx, snap.forces[w][s].fy);
      worst = std::max(worst, f / (mu * c.normal_force));
    }
  }
  return worst;
}

struct PositionResult {
  RunSummary summary;
  std::array<std::vector<double>, vehicle::kWheels> depth;  // scaled to the step's distance [m]
  std::vector<double> u;
};

// One wheelset position over the route: dynamics every step, wear every wheel revolution.
PositionResult run_position(const SimulationScene& sim, const Scene& scene, vehicle::ContactModel& contact,
                            const LookupContactModel* lookup, const DirectContactModel* direct,
                            const std::string& position, double step_distance, double max_duration,
                            const fs::path& trajectory_csv) {
  vehicle::WheelsetParameters parameters = sim.vehicle;
  parameters.semi_wheelbase = (position == "leading" ? 1.0 : -1.0) * std::abs(parameters.semi_wheelbase);
  const vehicle::TrackLayout track(sim.route, sim.irregularity, sim.rail_centre_distance);
  vehicle::WheelsetState initial;
  initial.y = sim.initial_y;
  vehicle::WheelsetSimulation wheelset(parameters, track, contact, sim.speed, sim.time_step, initial);
  WearAccumulator wear(scene);
  const double mu = scene.tangential.friction;
  const LookupCounts counts_before = lookup ? lookup->counts() : LookupCounts{};
  const std::uint64_t failures_before = direct ? direct->failures() : 0;

  PositionResult result;
  RunSummary& r = result.summary;
  r.position = position;
  double duration = track.length() / sim.speed;
  if (max_duration > 0.0) duration = std::min(duration, max_duration);
  const auto steps = static_cast<std::uint64_t>(std::llround(duration / sim.time_step));
  const double revolution = 2.0 * std::numbers::pi * parameters.nominal_radius;
  double next_wear = 0.0, next_row = 0.0, next_estimate = 0.0;
  r.stable_time_step_estimate = std::numeric_limits<double>::infinity();

  std::ostringstream csv;
  csv << "s_m,t_s,y_m,yaw_rad,y_relative_m,load_left_N,load_right_N,"
         "n_left_tread_N,n_left_flange_N,n_right_tread_N,n_right_flange_N,"
         "angle_left_tread_rad,angle_left_flange_rad,angle_right_tread_rad,angle_right_flange_rad,"
         "fy_left_tread_N,fy_left_flange_N,fy_right_tread_N,fy_right_flange_N,"
         "lateral_force_left_N,lateral_force_right_N,status\n";
  for (std::uint64_t k = 0; k < steps; ++k) {
    const auto t0 = Clock::now();
    wheelset.step();
    r.dynamics_wall_seconds += seconds_since(t0);
    ++r.steps;
    const vehicle::ContactSnapshot& snap = wheelset.snapshot();
    const double s = wheelset.distance() - sim.speed * sim.time_step;  // the snapshot's position
    r.status |= snap.status;
    r.max_creep_force_ratio = std::max(r.max_creep_force_ratio, slot_force_ratio(snap, mu));
    r.max_abs_y = std::max(r.max_abs_y, std::abs(snap.y_relative));
    if (s >= next_wear) {
      const auto tw = Clock::now();
      wear.sample(snap.y_relative, snap.load, snap.motion, revolution);
      r.wear_wall_seconds += seconds_since(tw);
      next_wear += revolution;
    }
    if (s >= next_estimate) {  // every 50 m: the contact stiffens in the curve
      r.stable_time_step_estimate = std::min(r.stable_time_step_estimate, wheelset.stable_time_step_estimate());
      next_estimate += 50.0;
    }
    if (s >= next_row) {
      const auto& c = snap.contacts;
      csv << fmt::format("{:.3f},{:.5f},{:.6e},{:.6e},{:.6e},{:.1f},{:.1f},", s, wheelset.time() - sim.time_step,
                         wheelset.state().y, wheelset.state().yaw, snap.y_relative, snap.load[0], snap.load[1]);
      csv << fmt::format("{:.1f},{:.1f},{:.1f},{:.1f},", c[0].slot[0].normal_force, c[0].slot[1].normal_force,
                         c[1].slot[0].normal_force, c[1].slot[1].normal_force);
      csv << fmt::format("{:.5f},{:.5f},{:.5f},{:.5f},", c[0].slot[0].contact_angle, c[0].slot[1].contact_angle,
                         c[1].slot[0].contact_angle, c[1].slot[1].contact_angle);
      csv << fmt::format("{:.1f},{:.1f},{:.1f},{:.1f},", snap.forces[0][0].fy, snap.forces[0][1].fy,
                         snap.forces[1][0].fy, snap.forces[1][1].fy);
      csv << fmt::format("{:.1f},{:.1f},{}\n", snap.lateral_force[0], snap.lateral_force[1], snap.status);
      next_row += sim.trajectory_interval;
    }
  }
  write_file(trajectory_csv, csv.str());

  r.simulated_seconds = wheelset.time();
  r.distance = wheelset.distance();
  if (!std::isfinite(r.stable_time_step_estimate)) r.stable_time_step_estimate = 0.0;
  if (lookup) {
    const LookupCounts& now = lookup->counts();
    r.queries = now.queries - counts_before.queries;
    r.out_of_range = now.out_of_range - counts_before.out_of_range;
    r.invalid_input = now.invalid_input - counts_before.invalid_input;
    for (std::size_t v = 0; v < 5; ++v) r.outside_axis[v] = now.outside_axis[v] - counts_before.outside_axis[v];
  }
  if (direct) r.contact_failures = direct->failures() - failures_before;
  r.wear_samples = wear.samples();
  r.wear_failures = wear.failures();
  r.wear_clipped_area = wear.clipped_area(0) + wear.clipped_area(1);
  // The route stands for the step's running distance: wear scales with distance.
  if (wear.distance() > 0.0) wear.scale(step_distance / wear.distance());
  result.u = wear.u();
  for (int w = 0; w < vehicle::kWheels; ++w) result.depth[static_cast<std::size_t>(w)] = wear.depth(w);
  return result;
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
      {"position", r.position},
      {"simulated_seconds", r.simulated_seconds},
      {"distance_m", r.distance},
      {"steps", r.steps},
      {"dynamics_wall_seconds", r.dynamics_wall_seconds},
      {"wear_wall_seconds", r.wear_wall_seconds},
      {"simulated_seconds_per_wall_second",
       r.dynamics_wall_seconds > 0.0 ? r.simulated_seconds / r.dynamics_wall_seconds : 0.0},
      {"stable_time_step_estimate_s", r.stable_time_step_estimate},
      {"max_creep_force_ratio", r.max_creep_force_ratio},
      {"max_abs_y_relative_m", r.max_abs_y},
      {"queries", r.queries},
      {"out_of_range", r.out_of_range},
      {"invalid_input", r.invalid_input},
      {"contact_failures", r.contact_failures},
      {"wear_samples", r.wear_samples},
      {"wear_failures", r.wear_failures},
      {"wear_clipped_area_m2", r.wear_clipped_area},
      {"status", status::describe(r.status)},
  };
  nlohmann::json axes = nlohmann::json::object();
  for (std::size_t v = 0; v < 5; ++v) axes[kLookupVariableNames[v]] = r.outside_axis[v];
  j["outside_axis"] = axes;
  return j;
}

void log_line(const SimulationOptions& options, const std::string& line) {
  if (options.log) *options.log << line << std::endl;
}

}  // namespace

double simulation_speed(const SimulationSummary& summary) {
  double simulated = 0.0, wall = 0.0;
  for (const auto& m : summary.models) {
    for (const auto& s : m.steps) {
      for (const auto& r : s.runs) {
        simulated += r.simulated_seconds;
        wall += r.dynamics_wall_seconds;
      }
    }
  }
  return wall > 0.0 ? simulated / wall : 0.0;
}

SimulationSummary run_simulation(const SimulationScene& sim, const SimulationOptions& options) {
  RAILTAB_CHECK(!options.out.empty(), "simulate: no output directory given");
  RAILTAB_CHECK(options.duration >= 0.0 && std::isfinite(options.duration), "simulate: --duration must be >= 0, got {}",
                options.duration);
  std::vector<std::string> models = options.models.empty() ? sim.models : options.models;
  for (const auto& m : models) parse_normal_model(m);  // throws naming a bad model
  const Scene contact = load_scene(sim.contact_scene);
  // The wheelset has no roll degree of freedom: its roll is the kinematic one at every y.
  RAILTAB_CHECK(contact.equilibrium_roll, "{}: the contact scene of a simulation needs [grid] equilibrium_roll = true",
                sim.contact_scene.string());

  SimulationSummary summary;
  summary.name = sim.name;
  summary.directory = options.out / sim.name;
  fs::create_directories(summary.directory);
  const double step_distance = sim.running_distance / sim.wear_steps;
  std::vector<WearSeries> final_series;

  for (const std::string& model : models) {
    ModelSummary ms;
    ms.model = model;
    fs::path worn_wheel;  // empty: the contact scene's wheel
    std::vector<double> cumulative;
    for (int k = 0; k < sim.wear_steps; ++k) {
      StepSummary step;
      step.step = k;
      step.running_distance = step_distance;
      const fs::path dir = summary.directory / model / fmt::format("step{}", k);
      fs::create_directories(dir);
      const std::string name = fmt::format("{}-{}-step{}", sim.name, model, k);
      const fs::path scene_file = dir / "scene.toml";
      write_file(scene_file, step_scene_text(sim, contact, model, worn_wheel, dir, name));
      const Scene scene = load_scene(scene_file);

      std::unique_ptr<vehicle::ContactModel> contact_model;
      const LookupContactModel* lookup = nullptr;
      const DirectContactModel* direct = nullptr;
      if (options.direct) {
        auto d = std::make_unique<DirectContactModel>(scene);
        direct = d.get();
        contact_model = std::move(d);
      } else {
        GenerateOptions g;
        g.scene = scene_file;
        g.output = dir / "table.h5";
        g.threads = options.threads;
        const auto tg = Clock::now();
        const SweepSummary s = generate_table(g);
        step.generate_seconds = seconds_since(tg);
        log_line(options, fmt::format("{} {} step {}: table {} ({} points, {} failures) in {:.1f} s", sim.name, model, k,
                                      g.output.string(), s.points_total, s.failures, step.generate_seconds));
        auto l = std::make_unique<LookupContactModel>(lookup::Table::load(g.output.string()));
        lookup = l.get();
        contact_model = std::move(l);
      }

      std::vector<PositionResult> results;
      for (const std::string& position : sim.positions) {
        results.push_back(run_position(sim, scene, *contact_model, lookup, direct, position, step_distance,
                                       options.duration, dir / fmt::format("trajectory_{}.csv", position)));
        const RunSummary& r = results.back().summary;
        log_line(options,
                 fmt::format("{} {} step {} {}: {:.1f} s simulated ({:.0f} m) in {:.2f} s wall: {:.1f} simulated s per "
                             "wall s; max |y| {:.2f} mm; out of range {} of {} queries; wear samples {} ({} failed)",
                             sim.name, model, k, position, r.simulated_seconds, r.distance, r.dynamics_wall_seconds,
                             r.dynamics_wall_seconds > 0 ? r.simulated_seconds / r.dynamics_wall_seconds : 0.0,
                             r.max_abs_y * 1e3, r.out_of_range, r.queries, r.wear_samples, r.wear_failures));
        if (r.stable_time_step_estimate > 0.0 && sim.time_step > r.stable_time_step_estimate) {
          log_line(options, fmt::format("warning: time_step {} s exceeds the stable RK4 step estimate {:.3e} s",
                                        sim.time_step, r.stable_time_step_estimate));
        }
        if (r.out_of_range > 0 || r.invalid_input > 0) {
          log_line(options, fmt::format("warning: {} table queries out of range, {} invalid (see summary.json "
                                        "outside_axis): widen the contact scene's grid",
                                        r.out_of_range, r.invalid_input));
        }
        step.runs.push_back(r);
      }

      // Equal left and right curves and forward-backward symmetry: one wheel profile is the
      // mean of both wheels and all positions.
      const std::vector<double>& u = results.front().u;
      std::vector<double> mean(u.size(), 0.0);
      const double weight = 1.0 / (static_cast<double>(results.size()) * vehicle::kWheels);
      for (const auto& r : results) {
        for (const auto& d : r.depth) {
          for (std::size_t i = 0; i < u.size(); ++i) mean[i] += weight * d[i];
        }
      }
      if (cumulative.empty()) cumulative.assign(u.size(), 0.0);
      for (std::size_t i = 0; i < u.size(); ++i) cumulative[i] += mean[i];
      step.worn_area = integrate(u, mean);
      step.cumulative_worn_area = integrate(u, cumulative);

      std::ostringstream csv;
      csv << "u_m";
      for (const auto& r : results) csv << ",depth_left_" << r.summary.position << "_m,depth_right_" << r.summary.position << "_m";
      csv << ",depth_mean_m,depth_cumulative_m\n";
      for (std::size_t i = 0; i < u.size(); ++i) {
        csv << fmt::format("{:.6f}", u[i]);
        for (const auto& r : results) csv << fmt::format(",{:.6e},{:.6e}", r.depth[0][i], r.depth[1][i]);
        csv << fmt::format(",{:.6e},{:.6e}\n", mean[i], cumulative[i]);
      }
      write_file(dir / "wear.csv", csv.str());
      write_file(dir / "worn_area.csv",
                 fmt::format("step,running_distance_m,worn_area_m2,worn_area_mm2,cumulative_worn_area_mm2\n{},{},{:.6e},{:.6f},{:.6f}\n",
                             k, step_distance, step.worn_area, step.worn_area * 1e6, step.cumulative_worn_area * 1e6));

      // The next step runs on the worn wheel (smoothed).
      const fs::path next = summary.directory / model / fmt::format("step{}", k + 1) / "wheel_worn.txt";
      fs::create_directories(next.parent_path());
      write_worn_profile(*wheel_profile(scene), u, mean, sim.profile_smoothing, next);
      worn_wheel = next;
      log_line(options, fmt::format("{} {} step {}: worn area {:.4f} mm2 (cumulative {:.4f} mm2 after {:.0f} km)", sim.name,
                                    model, k, step.worn_area * 1e6, step.cumulative_worn_area * 1e6,
                                    step_distance * (k + 1) / 1e3));
      ms.step_cumulative_depth.push_back(cumulative);
      ms.steps.push_back(std::move(step));
      ms.u = u;
    }
    ms.cumulative_depth = cumulative;
    double weight_sum = 0.0, moment = 0.0;
    for (std::size_t i = 0; i < cumulative.size(); ++i) {
      weight_sum += cumulative[i];
      moment += cumulative[i] * ms.u[i];
      if (cumulative[i] > ms.peak_depth) {
        ms.peak_depth = cumulative[i];
        ms.peak_u = ms.u[i];
      }
    }
    ms.centroid_u = weight_sum > 0.0 ? moment / weight_sum : 0.0;
    final_series.push_back({model, ms.u, cumulative, model.rfind("stripes", 0) == 0});
    summary.models.push_back(std::move(ms));
  }

  // summary.json and the chart of the cumulative radial wear (seed 001 Figs. 11-13).
  nlohmann::json j;
  j["scene"] = sim.name;
  j["contact_scene"] = sim.contact_scene.generic_string();
  j["contact"] = options.direct ? "direct (geometry + normal model + FASTSIM every evaluation)" : "table lookup";
  j["speed_m_per_s"] = sim.speed;
  j["time_step_s"] = sim.time_step;
  j["route_length_m"] = sim.route_length();
  j["running_distance_m"] = sim.running_distance;
  j["wear_steps"] = sim.wear_steps;
  j["lubrication_factor"] = sim.lubrication_factor;
  j["wear_scaling"] = "depth x (running distance per step / route distance sampled)";
  j["simulated_seconds_per_wall_second"] = simulation_speed(summary);
  for (const ModelSummary& m : summary.models) {
    nlohmann::json jm;
    jm["model"] = m.model;
    for (const StepSummary& s : m.steps) {
      nlohmann::json js = {{"step", s.step},
                           {"running_distance_m", s.running_distance},
                           {"worn_area_m2", s.worn_area},
                           {"worn_area_mm2", s.worn_area * 1e6},
                           {"cumulative_worn_area_mm2", s.cumulative_worn_area * 1e6},
                           {"generate_seconds", s.generate_seconds}};
      for (const RunSummary& r : s.runs) js["runs"].push_back(to_json(r));
      jm["steps"].push_back(js);
    }
    const double total = m.steps.empty() ? 0.0 : m.steps.back().cumulative_worn_area;
    jm["total_worn_area_m2"] = total;
    jm["total_worn_area_mm2"] = total * 1e6;
    jm["wear_centroid_u_m"] = m.centroid_u;
    jm["peak_depth_m"] = m.peak_depth;
    jm["peak_depth_u_m"] = m.peak_u;
    j["models"].push_back(jm);
  }
  write_file(summary.directory / "summary.json", j.dump(2) + "\n");
  try {
    draw_wear_chart(final_series, summary.directory / "wear.png",
                    fmt::format("{}: radial wear after {:.0f} km", sim.name, sim.running_distance / 1e3));
    // The evolution: every model after each wear step.
    for (int k = 0; k + 1 < sim.wear_steps; ++k) {
      std::vector<WearSeries> series;
      for (const ModelSummary& m : summary.models) {
        series.push_back({m.model, m.u, m.step_cumulative_depth[static_cast<std::size_t>(k)],
                          m.model.rfind("stripes", 0) == 0});
      }
      draw_wear_chart(series, summary.directory / fmt::format("wear_step{}.png", k),
                      fmt::format("{}: radial wear after {:.0f} km", sim.name, step_distance * (k + 1) / 1e3));
    }
  } catch (const Error& e) {
    log_line(options, fmt::format("warning: no chart: {}", e.what()));  // the CSVs are written
  }
  return summary;
}

}  // namespace railtab
