// SPDX-License-Identifier: Apache-2.0
// CSV files of the speed-against-accuracy measurement: one row per setting, per state, and the
// table memory rows; '#' comment lines name the reference, error measure and timing.
#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "speed_accuracy/speed_accuracy.hpp"
#include "core/check.hpp"
#include "table/output_file.hpp"

namespace railtab {

namespace {
std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("nan"); }

void header_comments(std::ostream& out, const SpeedAccuracyResult& r) {
  out << "# railtab chart: speed against accuracy (docs/speed-vs-accuracy.md)\n";
  out << "# reference: " << r.reference << "\n";
  out << "# set-up: " << r.setup << "\n";
  out << "# error measure: err_force = |F - F_ref| / |F_ref|, F = (fx, fy) creep force on the wheel summed over "
         "patches, states with creepage; medians (p90 = 90th percentile); tread = dy <= 6 mm, flange = dy >= 7 mm; "
         "err_area, err_pmax = |q/q_ref - 1| and err_angle = |angle - angle_ref| on states without creepage "
         "(CONTACT's dy = 7 mm a_none outlier excluded)\n";
  out << "# time: models = full chain geometry + normal + FASTSIM + Archard per state (median of repeats after a "
         "warm-up, then median over states), time_geometry = the geometry step alone; lookups = Table::query of "
         "both slots of the right wheel; one thread, steady_clock\n";
}
}  // namespace

void write_speed_accuracy_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path) {
  std::ostringstream out;
  header_comments(out, result);
  out << "label,kind,family,strips,elements,table_y_step_mm,table_creep_grid,time_us,time_tread_us,"
         "time_flange_us,time_geometry_us,time_contact_us,err_force,err_force_p90,err_force_tread,err_force_flange,err_area,"
         "err_pmax,err_angle_mrad,n_creep,n_normal,n_failed,table_file_bytes,table_memory_bytes,pareto_all,"
         "pareto_tread,pareto_flange,err_interp,err_interp_p90,reference\n";
  for (const SaRow& r : result.rows) {
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       r.label, r.kind, r.family, r.strips, r.elements, num(r.table_y_step * 1e3),
                       r.table_creep_grid, num(r.time_us), num(r.time_tread_us), num(r.time_flange_us),
                       num(r.time_geometry_us), num(r.time_contact_us), num(r.err_force), num(r.err_force_p90), num(r.err_force_tread),
                       num(r.err_force_flange), num(r.err_area), num(r.err_pmax), num(r.err_angle_mrad), r.n_creep,
                       r.n_normal, r.n_failed, r.file_bytes, r.memory_bytes, int(r.pareto_all),
                       int(r.pareto_tread), int(r.pareto_flange), num(r.err_interp), num(r.err_interp_p90),
                       result.contact_reference ? "contact" : result.exact_reference ? "halfspace" : "stripes");
  }
  write_text_file(path, out.str());
}

void write_states_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path) {
  std::ostringstream out;
  header_comments(out, result);
  out << "label,dy_mm,y_m,creep_set,xi,eta,phi_rad_per_m,flange,fx_N,fy_N,ref_fx_N,ref_fy_N,err_force,area_m2,"
         "ref_area_m2,pmax_Pa,ref_pmax_Pa,contact_angle_rad,ref_contact_angle_rad,time_us,fn_N,ref_fn_N\n";
  for (const SaStateRow& p : result.per_state) {
    const SaState& s = result.states[p.state];
    out << fmt::format("{},{:g},{:g},{},{:.6g},{:.6g},{:.6g},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                       result.rows[p.row].label, s.dy_mm, s.y, s.creep_set, s.xi, s.eta, s.phi, int(s.flange),
                       num(p.out.fx), num(p.out.fy), num(s.ref_fx), num(s.ref_fy), num(p.err_force), num(p.out.area),
                       num(s.ref_area), num(p.out.pmax), num(s.ref_pmax), num(p.out.angle), num(s.ref_angle),
                       num(p.time_us), num(p.out.fn), num(s.ref_fn));
  }
  write_text_file(path, out.str());
}

void write_table_memory_csv(const SpeedAccuracyResult& result, const std::filesystem::path& path) {
  std::ostringstream out;
  header_comments(out, result);
  out << "label,method,table_y_step_mm,table_creep_grid,table_file_bytes,table_memory_bytes,time_us,err_force,"
         "err_force_p90,err_force_tread,err_force_flange,err_area,err_angle_mrad,err_interp,err_interp_p90\n";
  for (const SaRow& r : result.rows) {
    if (r.kind != "lookup") continue;
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", r.label,
                       r.family.starts_with("lookup-linear") ? "linear" : "cubic", num(r.table_y_step * 1e3),
                       r.table_creep_grid, r.file_bytes, r.memory_bytes, num(r.time_us), num(r.err_force),
                       num(r.err_force_p90), num(r.err_force_tread), num(r.err_force_flange), num(r.err_area),
                       num(r.err_angle_mrad), num(r.err_interp), num(r.err_interp_p90));
  }
  write_text_file(path, out.str());
}

}  // namespace railtab
