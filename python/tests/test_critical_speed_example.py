# SPDX-License-Identifier: Apache-2.0
"""The worked example python/examples/critical_speed.py (docs/critical-speed.md): its closed forms
against its eigenvalue search, railtab.kalker_coefficients against Kalker's tabulated values, and a
reduced run on the STRIPES table whose linear bogie speed must fall inside the hunting bracket that
`railtab simulate` finds (two runs, 1.5 s each)."""
import importlib.util
import json
import math

import pytest

import railtab
from conftest import SOURCE_DIR

spec = importlib.util.spec_from_file_location("critical_speed", SOURCE_DIR / "python" / "examples" / "critical_speed.py")
example = importlib.util.module_from_spec(spec)
spec.loader.exec_module(example)

# A coned wheelset held to a rigid frame: the suspension of tables/sim/tangent.toml's vehicle.
WHEELSET = dict(r0=0.46, e0=0.75, conicity=0.2, k_y=5.0e6, k_psi=2.4e6, m=1500.0, inertia=700.0)


@pytest.mark.parametrize("f11, f22", [(10e6, 8e6), (2e6, 6e6), (30e6, 30e6)])
def test_routh_hurwitz_closed_form_equals_the_eigenvalue_crossing(f11, f22):
    closed = example.wheelset_linear(**WHEELSET, f11=f11, f22=f22)
    searched = example.critical_speed(lambda v: example.wheelset_matrix(v, **WHEELSET, f11=f11, f22=f22))
    assert closed is not None and searched is not None
    assert searched == pytest.approx(closed, rel=1e-5)


def test_stiff_creep_tends_to_wickens_formula():
    wickens = example.wickens_stiff_creep(**WHEELSET)
    # sqrt(r0 e0 (k_psi + e0^2 k_y) / (lambda (I + m e0^2))) by hand: 76.32 m/s
    assert wickens == pytest.approx(math.sqrt(0.46 * 0.75 * (2.4e6 + 0.5625 * 5e6) / (0.2 * (700 + 1500 * 0.5625))))
    assert wickens == pytest.approx(76.318, abs=1e-3)
    assert example.wheelset_linear(**WHEELSET, f11=1e13, f22=1e13) == pytest.approx(wickens, rel=1e-5)


def test_bogie_with_rigid_frame_is_two_single_wheelsets():
    """A frame too heavy to move and no spin: each wheelset is the single wheelset on a rigid frame."""
    p = {k: 1.0 for k in example.VEHICLE_KEYS}
    p.update(mass=1500.0, yaw_inertia=700.0, primary_lateral_stiffness=5e6, primary_longitudinal_stiffness=1.2e6,
             primary_lateral_damping=0.0, axlebox_semi_spacing=1.0, semi_wheelbase=1.35, frame_mass=1e12,
             frame_yaw_inertia=1e12, secondary_lateral_stiffness=1e14, secondary_lateral_damping=1e13,
             secondary_yaw_stiffness=1e14, secondary_yaw_damping=1e13)
    bogie = example.critical_speed(lambda v: example.bogie_matrix(v, 0.46, 0.75, 0.2, 10e6, 8e6, 0.0, p))
    single = example.wheelset_linear(**WHEELSET, f11=10e6, f22=8e6)
    assert bogie == pytest.approx(single, rel=1e-4)


def test_kalker_coefficients_reproduce_the_table():
    # Kalker (1990) Table E.3 at nu = 0.25: a/b = 0.5 and b/a = 0.5
    assert railtab.kalker_coefficients(0.5, 0.25) == pytest.approx((3.62, 3.01, 0.929), rel=1e-9)
    assert railtab.kalker_coefficients(2.0, 0.25) == pytest.approx((5.10, 4.90, 2.62), rel=1e-9)
    with pytest.raises(railtab.Error):
        railtab.kalker_coefficients(-1.0, 0.3)


def test_example_on_the_stripes_table_brackets_the_linear_speed(stripes_table, railtab_program, tmp_path, capsys):
    example.main(["--table", str(stripes_table), "--scene", str(SOURCE_DIR / "tables" / "default_stripes.toml"),
                  "--railtab", railtab_program, "--speeds", "20,40", "--duration", "1.5", "--bisections", "0",
                  "--workdir", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert 0.1 < out["equivalent_conicity"] < 0.5
    for key in ("wickens_stiff_creep_m_per_s", "wheelset_kalker_m_per_s", "bogie_kalker_m_per_s"):
        assert out[key] is not None and math.isfinite(out[key]) and out[key] > 0
    sim = out["simulate"]
    assert sim["fastest_stable_m_per_s"] == 20.0 and sim["slowest_hunting_m_per_s"] == 40.0
    # the linear bogie with spin creep predicts the onset the simulation brackets
    assert 20.0 < out["bogie_kalker_m_per_s"] < 40.0
