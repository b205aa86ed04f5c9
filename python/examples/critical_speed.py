# SPDX-License-Identifier: Apache-2.0
"""Worked example: a wheelset's and a bogie's linear critical speed from one contact table, beside
the hunting onset that `railtab simulate` finds by raising the speed on the same contact scene.

    PYTHONPATH=build/release/python python3 python/examples/critical_speed.py \
        --table default.h5 --scene tables/default.toml --railtab build/release/generator/railtab

Linear part (docs/critical-speed.md):
- equivalent conicity lambda_e, e0, r0 from `railtab conicity --table T --json` at --amplitude;
- creep coefficients f11 = G c^2 C11, f22 = G c^2 C22 per wheel (Kalker's linear theory on the
  table's contact ellipse at the centred wheelset: semi-axes a, b of slot 0 at the vehicle's wheel
  load; C11, C22 from railtab.kalker_coefficients), and for comparison the table's own slope
  -d fx / d xi, -d fy / d eta at zero creepage (its interpolant);
- the lateral stiffness of the normal forces (gravitational stiffness) from the table;
- suspension, masses and geometry from the [vehicle] of a `railtab simulate` scene, so that the
  linear numbers and the simulated onset belong to the same vehicle.
Three linear critical speeds: Wickens' classical formula of a single wheelset held to a rigid frame
by lateral and yaw springs, stiff creep (Wickens 1965; Wickens 2003),
    V_c^2 = (r0 e0 / lambda_e) (k_psi + e0^2 k_y) / (I + m e0^2);
the same wheelset with finite creep coefficients (the Routh-Hurwitz condition of its 4th-order
characteristic polynomial, closed form); and the bogie of `railtab simulate` linearised
(6 degrees of freedom, eigenvalues), which is the number comparable with the simulated onset.

Simulated part: `railtab simulate` on a tangent track at a ladder of speeds, from an initial
lateral offset of all bodies (--initial-y); a run hunts if the leading wheelset's lateral
oscillation grows (largest |y| over the last quarter of the run above that over the first
quarter). Then bisection between the fastest stable and slowest hunting speed.
"""
import argparse
import csv
import json
import math
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np

import railtab

VEHICLE_KEYS = ("mass", "yaw_inertia", "primary_lateral_stiffness", "primary_longitudinal_stiffness",
                "primary_lateral_damping", "axlebox_semi_spacing", "semi_wheelbase", "nominal_radius",
                "running_circle_q", "frame_mass", "frame_yaw_inertia", "frame_cg_height", "body_mass",
                "body_cg_height", "bogie_semi_spacing", "secondary_lateral_stiffness",
                "secondary_lateral_damping", "secondary_yaw_stiffness", "secondary_yaw_damping")


def wickens_stiff_creep(r0, e0, conicity, k_y, k_psi, m, inertia):
    """Critical speed [m/s] of a wheelset held by lateral (k_y) and yaw (k_psi) springs to a frame
    moving straight at constant speed, creep coefficients -> infinity, no gravitational stiffness:
    Wickens' classical result."""
    return math.sqrt(r0 * e0 * (k_psi + e0 * e0 * k_y) / (conicity * (inertia + m * e0 * e0)))


def wheelset_linear(r0, e0, conicity, k_y, k_psi, m, inertia, f11, f22):
    """Critical speed [m/s] of the same wheelset with finite creep coefficients f11, f22 per wheel
    [N]: the Routh-Hurwitz condition a3 a2 a1 = a1^2 a4 + a3^2 a0 of
        m y'' + 2 f22 / V y' + k_y y - 2 f22 psi = 0
        I psi'' + 2 f11 e0^2 / V psi' + k_psi psi + 2 f11 e0 conicity / r0 y = 0
    solved for V^2. None if no speed is critical (the wheelset is stable at every speed)."""
    e, lam, f1, f2, kp, ky, i = e0, conicity, f11, f22, k_psi, k_y, inertia
    num = 4 * e * r0 * (i * e**2 * f1 * f2 * ky + i * f2**2 * kp + e**4 * f1**2 * ky * m + e**2 * f1 * f2 * kp * m)
    den = (-i**2 * e * ky**2 * r0 + 4 * i**2 * f2**2 * lam + 8 * i * e**2 * f1 * f2 * lam * m
           + 2 * i * e * kp * ky * m * r0 + 4 * e**4 * f1**2 * lam * m**2 - e * kp**2 * m**2 * r0)
    return math.sqrt(num / den) if den > 0 else None


def wheelset_matrix(v, r0, e0, conicity, k_y, k_psi, m, inertia, f11, f22, k_grav=0.0):
    """First-order system matrix of the single wheelset above, states (y, psi, y', psi')."""
    stiffness = np.array([[k_y + k_grav, -2 * f22], [2 * f11 * e0 * conicity / r0, k_psi]])
    damping = np.diag([2 * f22 / v, 2 * f11 * e0 * e0 / v])
    return _first_order(np.diag([m, inertia]), damping, stiffness)


def bogie_matrix(v, r0, e0, conicity, f11, f22, k_grav, p, f23=0.0, spin_slope=0.0):
    """First-order system matrix of the bogie of `railtab simulate` (docs/vehicle-model.md, "The
    bogie") linearised on tangent track: states (y0, psi0, y1, psi1, yf, psif) and rates; wheelset
    0 leads at +a, 1 trails at -a. Creep per wheel: fx = -f11 xi, fy = -f22 eta - f23 phi,
    mz = f23 eta (Kalker's linear theory without C33), with the spin of the wheels
    phi = (-Omega sin(g) + psi' cos(g)) / V, so that the wheelset's lateral force gains
    f23 spin_slope / r0 y - 2 f23 / V psi' (spin_slope = d(sin g_left + sin g_right)/dy) and its
    yaw moment 2 f23 (y' / V - psi); the normal forces' lateral stiffness k_grav per wheelset."""
    a = p["semi_wheelbase"]
    k_y, c_y = p["primary_lateral_stiffness"], p["primary_lateral_damping"]
    k_psi = 2 * p["primary_longitudinal_stiffness"] * p["axlebox_semi_spacing"] ** 2
    mass = np.diag([p["mass"], p["yaw_inertia"], p["mass"], p["yaw_inertia"], p["frame_mass"], p["frame_yaw_inertia"]])
    k = np.zeros((6, 6))
    c = np.zeros((6, 6))
    for i, ai in enumerate((a, -a)):
        yi, pi = 2 * i, 2 * i + 1
        # creep on the wheelset
        k[yi, yi] += k_grav
        k[yi, pi] += -2 * f22
        c[yi, yi] += 2 * f22 / v
        k[pi, yi] += 2 * f11 * e0 * conicity / r0
        c[pi, pi] += 2 * f11 * e0 * e0 / v
        # spin creep: lateral force from the wheels' spin, yaw moment from the lateral creepage
        k[yi, yi] -= f23 * spin_slope / r0
        c[yi, pi] += 2 * f23 / v
        c[pi, yi] -= 2 * f23 / v
        k[pi, pi] += 2 * f23
        # primary lateral spring and damper on the deflection d = y_i - y_f - a_i psi_f
        g = np.zeros(6)
        g[yi], g[4], g[5] = 1.0, -1.0, -ai
        for row, weight in ((yi, 1.0), (4, -1.0), (5, -ai)):
            k[row] += weight * k_y * g
            c[row] += weight * c_y * g
        # primary yaw spring on psi_i - psi_f
        h = np.zeros(6)
        h[pi], h[5] = 1.0, -1.0
        k[pi] += k_psi * h
        k[5] -= k_psi * h
    k[4, 4] += p["secondary_lateral_stiffness"]
    c[4, 4] += p["secondary_lateral_damping"]
    k[5, 5] += p["secondary_yaw_stiffness"]
    c[5, 5] += p["secondary_yaw_damping"]
    return _first_order(mass, c, k)


def _first_order(mass, damping, stiffness):
    n = mass.shape[0]
    inv = np.linalg.inv(mass)
    return np.block([[np.zeros((n, n)), np.eye(n)], [-inv @ stiffness, -inv @ damping]])


def critical_speed(matrix_at, v_lo=1.0, v_hi=300.0, steps=300):
    """Lowest speed in [v_lo, v_hi] where the largest real part of the eigenvalues of matrix_at(V)
    crosses zero (scan, then bisection to 1e-6 relative); None if stable throughout."""
    growth = lambda v: np.max(np.linalg.eigvals(matrix_at(v)).real)
    speeds = np.geomspace(v_lo, v_hi, steps)
    previous = speeds[0]
    if growth(previous) > 0:
        raise ValueError(f"unstable already at the lowest speed {v_lo} m/s")
    for v in speeds[1:]:
        if growth(v) > 0:
            lo, hi = previous, v
            while hi - lo > 1e-6 * hi:
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if growth(mid) > 0 else (mid, hi)
            return 0.5 * (lo + hi)
        previous = v
    return None


def run(cmd):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"critical_speed: {' '.join(map(str, cmd))} failed ({done.returncode}): {done.stderr.strip()}")
    return done.stdout


def vehicle_parameters(sim_scene):
    with open(sim_scene, "rb") as f:
        vehicle = tomllib.load(f).get("vehicle", {})
    missing = [k for k in VEHICLE_KEYS if k not in vehicle]
    if missing:
        sys.exit(f"critical_speed: {sim_scene}: [vehicle] lacks {', '.join(missing)}")
    return {k: float(vehicle[k]) for k in VEHICLE_KEYS}


def static_wheel_load(p, gravity=9.81):
    """(m + M) g / 2 with M = body/4 + frame/2 (docs/vehicle-model.md, "Suspension and the car body")."""
    return (p["mass"] + p["body_mass"] / 4 + p["frame_mass"] / 2) * gravity / 2


def contact_at_centre(table_path, scene_path, centre, load):
    """Per-wheel creep coefficients and the gravitational stiffness of the centred wheelset."""
    with open(scene_path, "rb") as f:
        material = tomllib.load(f)["material"]
    young, poisson = float(material["youngs_modulus"]), float(material["poisson_ratio"])
    shear = young / (2 * (1 + poisson))
    table = railtab.Table.load(str(table_path))
    result = {"shear_modulus_Pa": shear, "poisson_ratio": poisson, "wheel_load_N": load, "wheels": {}}
    f11_k, f22_k, f23_k, f11_t, f22_t, f23_t = [], [], [], [], [], []
    for wheel in ("left", "right"):
        r = table.query(wheel, y=centre, load=load, slot=0, derivatives=True, as_xarray=False)
        a, b = float(np.ravel(r["a"])[0]), float(np.ravel(r["b"])[0])
        c11, c22, c23 = railtab.kalker_coefficients(a / b, poisson)
        f11_k.append(shear * a * b * c11)
        f22_k.append(shear * a * b * c22)
        f23_k.append(shear * (a * b) ** 1.5 * c23)
        f11_t.append(-float(np.ravel(r["d_fx_d_xi"])[0]))
        f22_t.append(-float(np.ravel(r["d_fy_d_eta"])[0]))
        f23_t.append(-float(np.ravel(r["d_fy_d_phi"])[0]))
        result["wheels"][wheel] = {"a_m": a, "b_m": b, "normal_force_N": float(np.ravel(r["normal_force"])[0]),
                                   "C11": c11, "C22": c22, "C23": c23, "f11_kalker_N": f11_k[-1],
                                   "f22_kalker_N": f22_k[-1], "f23_kalker_N_m": f23_k[-1], "f11_table_N": f11_t[-1],
                                   "f22_table_N": f22_t[-1], "f23_table_N_m": f23_t[-1],
                                   "d_mz_d_eta_table_N_m": float(np.ravel(r["d_mz_d_eta"])[0])}
    result["f11_kalker_N"], result["f22_kalker_N"] = float(np.mean(f11_k)), float(np.mean(f22_k))
    result["f23_kalker_N_m"] = float(np.mean(f23_k))
    result["f11_table_N"], result["f22_table_N"] = float(np.mean(f11_t)), float(np.mean(f22_t))
    result["f23_table_N_m"] = float(np.mean(f23_t))
    # Lateral force of the normal forces on the wheelset, sum over wheels and slots of -N sin(g)
    # in track axes, at the table's y nodes next to the centre: its slope is the gravitational stiffness.
    dy = 0.5e-3
    ys = np.array([centre - dy, centre + dy])
    lateral, sines = np.zeros(2), np.zeros(2)
    for wheel in ("left", "right"):
        r = table.query(wheel, y=ys, load=load, track_forces=True, as_xarray=False)
        n = np.asarray(r["normal_force"]).reshape(2, -1)
        t = np.asarray(r["track_lateral_force"]).reshape(2, -1)
        lateral += np.where(n > 0, t, 0.0).sum(axis=1)
        sines += np.sin(np.asarray(r["track_contact_angle"]).reshape(2, -1)[:, 0])  # the tread slot's angle
    result["gravitational_stiffness_N_per_m"] = float(-(lateral[1] - lateral[0]) / (2 * dy))
    # d(sin g_left + sin g_right)/dy, g in track axes: the spin of the wheels grows with y
    result["spin_slope_per_m"] = float((sines[1] - sines[0]) / (2 * dy))
    return result


def simulate_once(program, scene_path, vehicle_scene, speed, initial_y, duration, workdir, time_step):
    """One `railtab simulate` run on a tangent track; returns (growth ratio, largest |y| [m])."""
    with open(vehicle_scene, "rb") as f:
        vehicle = tomllib.load(f)["vehicle"]
    with open(scene_path, "rb") as f:
        model = tomllib.load(f)["contact"]["normal_model"]
    name = f"v{speed:.3f}".replace(".", "_")
    lines = ["[simulation]", f'name = "{name}"', f'contact_scene = "{Path(scene_path).resolve()}"',
             f'dynamics_model = "{model}"', 'wear_post_processors = ["hertz"]', 'positions = ["leading"]',
             f"speed = {speed!r}", f"time_step = {time_step!r}", f"initial_y = {initial_y!r}",
             "running_distance = 1.0", "trajectory_interval = 0.05", "", "[vehicle]"]
    lines += [f"{k} = {float(v)!r}" for k, v in vehicle.items()]
    lines += ["", "[route]", "rail_centre_distance = 1.5", "", "[[route.section]]", 'kind = "tangent"',
              f"length = {speed * duration + 10.0!r}", ""]
    scene_file = Path(workdir) / f"{name}.toml"
    scene_file.write_text("\n".join(lines))
    run([program, "simulate", str(scene_file), "--out", str(workdir), "--duration", str(duration), "--quiet"])
    with open(Path(workdir) / name / "shared" / "step0" / "trajectory.csv") as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["t_s"]) for r in rows])
    y = np.array([float(r["leading_y_relative_m"]) for r in rows])
    quarter = t[-1] / 4
    first = np.max(np.abs(y[t <= quarter]))
    last = np.max(np.abs(y[t >= 3 * quarter]))
    return last / first, float(np.max(np.abs(y)))


def hunting_onset(program, scene_path, vehicle_scene, speeds, initial_y, duration, workdir, bisections,
                  time_step):
    """Runs the ladder, then bisects; returns the runs and the bracket (fastest stable, slowest hunting)."""
    runs = []

    def one(v):
        ratio, peak = simulate_once(program, scene_path, vehicle_scene, v, initial_y, duration, workdir, time_step)
        runs.append({"speed_m_per_s": v, "growth_ratio": ratio, "max_abs_y_m": peak, "hunting": bool(ratio > 1.0)})
        return ratio > 1.0

    stable, hunting = None, None
    for v in sorted(speeds):
        if one(v):
            hunting = v
            break
        stable = v
    if stable is not None and hunting is not None:
        for _ in range(bisections):
            mid = 0.5 * (stable + hunting)
            if one(mid):
                hunting = mid
            else:
                stable = mid
    return runs, stable, hunting


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--table", required=True, help="contact table (railtab generate)")
    parser.add_argument("--scene", required=True, help="the table's contact scene (material; simulate's contact)")
    parser.add_argument("--vehicle", default=None, help="a railtab simulate scene whose [vehicle] is used "
                        "(default tables/sim/tangent.toml beside --scene)")
    parser.add_argument("--railtab", default="railtab", help="the railtab program")
    parser.add_argument("--amplitude", type=float, default=0.002, help="conicity amplitude [m] (default 0.002)")
    parser.add_argument("--speeds", default="", help="simulate ladder [m/s], comma separated; empty: linear part only")
    parser.add_argument("--initial-y", type=float, default=0.002, help="initial lateral offset [m] of the runs")
    parser.add_argument("--duration", type=float, default=3.0, help="simulated seconds per run")
    parser.add_argument("--time-step", type=float, default=0.5e-3, help="RK4 step [s] of the runs")
    parser.add_argument("--bisections", type=int, default=3, help="bisection steps inside the ladder's bracket")
    parser.add_argument("--workdir", default="critical_speed_runs", help="directory of the simulate runs")
    parser.add_argument("--json", action="store_true", help="print JSON")
    args = parser.parse_args(argv)

    vehicle_scene = args.vehicle or str(Path(args.scene).parent / "sim" / "tangent.toml")
    p = vehicle_parameters(vehicle_scene)
    k_psi = 2 * p["primary_longitudinal_stiffness"] * p["axlebox_semi_spacing"] ** 2
    load = static_wheel_load(p)

    con = json.loads(run([args.railtab, "conicity", "--table", args.table, "--json",
                          "--amplitudes", repr(args.amplitude)]))
    conicity, e0, r0, centre = con["equivalent_conicity"][0], con["e0_m"], con["r0_m"], con["centre_m"]
    if conicity is None:
        sys.exit(f"critical_speed: {args.table}: no equivalent conicity at amplitude {args.amplitude} m")
    contact = contact_at_centre(args.table, args.scene, centre, load)
    f11, f22, k_grav = contact["f11_kalker_N"], contact["f22_kalker_N"], contact["gravitational_stiffness_N_per_m"]
    f23, spin_slope = contact["f23_kalker_N_m"], contact["spin_slope_per_m"]
    out = {
        "table": args.table, "vehicle": vehicle_scene, "amplitude_m": args.amplitude,
        "equivalent_conicity": conicity, "e0_m": e0, "r0_m": r0, "k_psi_N_m_per_rad": k_psi, "contact": contact,
        "wickens_stiff_creep_m_per_s": wickens_stiff_creep(r0, e0, conicity, p["primary_lateral_stiffness"], k_psi,
                                                           p["mass"], p["yaw_inertia"]),
        "wheelset_kalker_m_per_s": wheelset_linear(r0, e0, conicity, p["primary_lateral_stiffness"], k_psi,
                                                   p["mass"], p["yaw_inertia"], f11, f22),
        "bogie_no_spin_m_per_s": critical_speed(lambda v: bogie_matrix(v, r0, e0, conicity, f11, f22, k_grav, p)),
        "bogie_kalker_m_per_s": critical_speed(lambda v: bogie_matrix(v, r0, e0, conicity, f11, f22, k_grav, p,
                                                                      f23, spin_slope)),
        "bogie_table_creep_m_per_s": critical_speed(lambda v: bogie_matrix(
            v, r0, e0, conicity, contact["f11_table_N"], contact["f22_table_N"], k_grav, p,
            contact["f23_table_N_m"], spin_slope)),
    }
    if args.speeds:
        Path(args.workdir).mkdir(parents=True, exist_ok=True)
        speeds = [float(s) for s in args.speeds.split(",")]
        runs, stable, hunting = hunting_onset(args.railtab, args.scene, vehicle_scene, speeds, args.initial_y,
                                              args.duration, args.workdir, args.bisections, args.time_step)
        out["simulate"] = {"initial_y_m": args.initial_y, "duration_s": args.duration, "runs": runs,
                           "fastest_stable_m_per_s": stable, "slowest_hunting_m_per_s": hunting}
    if args.json:
        print(json.dumps(out, indent=1))
        return
    print(f"table {args.table}, vehicle {vehicle_scene}")
    print(f"equivalent conicity {conicity:.4f} at {args.amplitude * 1e3:g} mm, e0 {e0:.4f} m, r0 {r0:.4f} m")
    print(f"wheel load {load / 1e3:.2f} kN: f11 {f11 / 1e6:.2f} MN, f22 {f22 / 1e6:.2f} MN per wheel (Kalker on the "
          f"table's ellipse); table slopes f11 {contact['f11_table_N'] / 1e6:.2f} MN, f22 {contact['f22_table_N'] / 1e6:.2f} MN;"
          f" gravitational stiffness {k_grav / 1e6:.3f} MN/m")
    show = lambda v: "stable at every speed up to 300 m/s" if v is None else f"{v:.2f} m/s ({v * 3.6:.1f} km/h)"
    print(f"linear critical speed, Wickens (single wheelset, stiff creep): {show(out['wickens_stiff_creep_m_per_s'])}")
    print(f"linear critical speed, single wheelset, Kalker creep:        {show(out['wheelset_kalker_m_per_s'])}")
    print(f"f23 {f23 / 1e3:.2f} kN m (Kalker), {contact['f23_table_N_m'] / 1e3:.2f} kN m (table); "
          f"d(sin g_l + sin g_r)/dy {spin_slope:.2f} 1/m")
    print(f"linear critical speed, bogie, Kalker without spin creep:     {show(out['bogie_no_spin_m_per_s'])}")
    print(f"linear critical speed, bogie of railtab simulate, Kalker:    {show(out['bogie_kalker_m_per_s'])}")
    print(f"linear critical speed, bogie, the table's creep slopes:      {show(out['bogie_table_creep_m_per_s'])}")
    if "simulate" in out:
        for r in out["simulate"]["runs"]:
            print(f"  simulate {r['speed_m_per_s']:.3f} m/s: growth {r['growth_ratio']:.3f}, max |y| "
                  f"{r['max_abs_y_m'] * 1e3:.2f} mm, {'hunting' if r['hunting'] else 'stable'}")
        s = out["simulate"]
        print(f"hunting onset (railtab simulate, initial y {args.initial_y * 1e3:g} mm): between "
              f"{s['fastest_stable_m_per_s']} and {s['slowest_hunting_m_per_s']} m/s")


if __name__ == "__main__":
    main()
