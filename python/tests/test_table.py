# SPDX-License-Identifier: Apache-2.0
"""railtab.Table: loading, vectorised queries against the fixture's known values, units, status."""
import os
import subprocess

import numpy as np
import pytest

import railtab
from conftest import SOURCE_DIR, fixture_value

# Output index within its part (table_fixture.hpp numbers outputs per part).
FX = ("creep", 2, 0)  # (part name, part index, output index in part)


def test_load_describes_the_table(fixture_table):
    t = railtab.Table.load(fixture_table)
    assert t.parts == ["geometry", "normal", "creep", "wear"]
    assert list(t.axes) == ["y", "xi", "eta", "phi"]
    assert len(t.axes["y"]) == 9 and t.axes["y"][0] == pytest.approx(-0.01)
    assert t.fixed_axes == {"roll": 0.0, "load": 78500.0}
    assert t.n_slots == 2 and t.method == "linear"
    assert "fx" in t.outputs() and "wear_rate" in t.outputs()


def test_load_errors_name_the_file(tmp_path, fixture_table):
    with pytest.raises(OSError, match="nothing.h5"):
        railtab.Table.load(tmp_path / "nothing.h5")
    bad = tmp_path / "bad.h5"
    bad.write_text("not hdf5")
    with pytest.raises(OSError, match="bad.h5"):
        railtab.Table.load(bad)
    truncated = tmp_path / "truncated.h5"   # a real table cut short: corrupt, not "not HDF5"
    truncated.write_bytes(fixture_table.read_bytes()[:4000])
    with pytest.raises(OSError, match=r"truncated.h5.*(truncated|corrupt)"):
        railtab.Table.load(truncated)
    with pytest.raises(OSError, match="not a regular file"):
        railtab.Table.load(tmp_path)           # a directory
    with pytest.raises(ValueError, match="method"):
        railtab.Table.load(bad, method="spline")


def test_constructor_loads_a_path_and_refuses_anything_else(tmp_path, fixture_table):
    # Table(path) is Table.load(path): the same table, the same errors naming the input.
    t = railtab.Table(fixture_table)
    assert t.path == str(fixture_table) and list(t.axes) == ["y", "xi", "eta", "phi"]
    assert railtab.Table(str(fixture_table), method="cubic").method == "cubic"
    with pytest.raises(OSError, match=r"x\.h5.*no such file"):
        railtab.Table(tmp_path / "x.h5")
    with pytest.raises(OSError, match=r"it is a directory, not a regular file"):
        railtab.Table(tmp_path)
    fifo = tmp_path / "fifo.h5"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match=r"fifo\.h5.*it is a FIFO, not a regular file"):
        railtab.Table(fifo)                    # at once: nothing opens it
    with pytest.raises(OSError, match=r"/dev/null.*it is a character device"):
        railtab.Table("/dev/null")
    for wrong in (None, 42, 1.5, ["x.h5"], open(fixture_table, "rb")):
        with pytest.raises(TypeError, match=r"^path must be a file name \(str, bytes or os\.PathLike\), got"):
            railtab.Table(wrong)
        with pytest.raises(TypeError, match=r"^path must be a file name"):
            railtab.Table.load(wrong)
    with pytest.raises(TypeError, match=r"^method must be 'linear', 'cubic' or 'monotone-cubic', got int 3"):
        railtab.Table(fixture_table, 3)
    with pytest.raises(TypeError):
        railtab.Table()                        # Python's own: missing argument 'path'


def test_scene_constructor_loads_a_path_and_refuses_anything_else(tmp_path):
    scene = railtab.Scene(SOURCE_DIR / "tables" / "default_stripes.toml")
    assert scene.name == railtab.Scene.load(SOURCE_DIR / "tables" / "default_stripes.toml").name
    with pytest.raises(railtab.Error, match=r"nothing\.toml"):
        railtab.Scene(tmp_path / "nothing.toml")
    with pytest.raises(TypeError, match=r"^path must be a file name"):
        railtab.Scene(7)


def test_vectorised_query_reproduces_the_fixture(fixture_table):
    t = railtab.Table.load(fixture_table)
    rng = np.random.default_rng(1)
    y = rng.uniform(-0.01, 0.01, 1000)                 # linear in y: exact between nodes
    xi = rng.choice(t.axes["xi"], 1000)                # at nodes: exact whatever the shape in xi
    eta = rng.choice(t.axes["eta"], 1000)
    for wheel, code in (("left", 0), ("right", 1)):
        r = t.query(wheel, y=y, xi=xi, eta=eta, as_xarray=False)
        assert r["fx"].shape == (1000, 2) and r.units["fx"] == "N"
        for slot in (0, 1):
            np.testing.assert_allclose(r["fx"][:, slot], fixture_value(code, 2, 0, slot, y, xi, eta),
                                       rtol=1e-12, atol=1e-12)
            # geometry is tabulated on y only
            np.testing.assert_allclose(r["rolling_radius"][:, slot], fixture_value(code, 0, 1, slot, y),
                                       rtol=1e-12, atol=1e-12)
        assert (r["status"] == 1).all()  # the fixture's status: converged everywhere


def test_wheel_array_slot_and_broadcasting(fixture_table):
    t = railtab.Table.load(fixture_table)
    y = np.linspace(-0.008, 0.008, 5)
    xi = t.axes["xi"]
    r = t.query(np.array(["left", "right"])[:, None, None], y=y[None, :, None], xi=xi[None, None, :],
                as_xarray=False)
    assert r["fx"].shape == (2, 5, len(xi), 2)
    left = t.query("left", y=y[:, None], xi=xi[None, :], as_xarray=False)
    np.testing.assert_array_equal(r["fx"][0], left["fx"])
    np.testing.assert_allclose(r["fx"][1, :, :, 1], fixture_value(1, 2, 0, 1, y[:, None], xi[None, :]), rtol=1e-12)
    one = t.query("left", y=y[:, None], xi=xi[None, :], slot=1, as_xarray=False)
    assert one["fx"].shape == (5, len(xi), 1)
    np.testing.assert_array_equal(one["fx"][..., 0], left["fx"][..., 1])
    scalar = t.query(1, y=0.001, xi=0.0, as_xarray=False)
    assert scalar["fx"].shape == (2,)


def test_status_out_of_range_and_invalid_input(fixture_table):
    t = railtab.Table.load(fixture_table)
    r = t.query("left", y=[0.0, 0.02, np.nan, 0.0], load=[78500.0, 78500.0, 78500.0, 60000.0], as_xarray=False)
    text = railtab.decode_status(r["status"][:, 0])
    assert text[0] == "converged"
    assert "out_of_range" in text[1]                    # y beyond the table: clamped, flagged
    assert "invalid_input" in text[2] and r["fx"][2, 0] == 0.0
    assert "out_of_range" in text[3]                    # load is fixed at 78500 N in this table
    np.testing.assert_array_equal(railtab.has_flag(r["status"][:, 0], "out_of_range"), [False, True, False, True])
    # the clamped value is the edge value, never extrapolated
    edge = t.query("left", y=0.01, as_xarray=False)
    np.testing.assert_array_equal(r["fx"][1], edge["fx"])


def test_bad_arguments_are_refused_with_names(fixture_table):
    t = railtab.Table.load(fixture_table)
    with pytest.raises(TypeError, match="y is an axis"):
        t.query("left", xi=0.001)
    with pytest.raises(ValueError, match="wheel"):
        t.query("middle", y=0.0)
    with pytest.raises(ValueError, match="wheel"):
        t.query(2, y=0.0)
    with pytest.raises(ValueError, match="slot: must be a whole number in .0, 1., got 5"):
        t.query("left", y=0.0, slot=5)
    with pytest.raises(ValueError, match=r"y \(3,\), xi \(4,\)"):   # named, not numpy's "arg 1", "arg 3"
        t.query("left", y=np.zeros(3), xi=np.zeros(4))   # shapes that do not broadcast
    with pytest.raises(ValueError, match=r"wheel \(2,\), y \(3,\)"):
        t.query(["left", "right"], y=np.zeros(3))
    with pytest.raises(TypeError, match="xi must be real"):
        t.query("left", y=0.0, xi=np.array([1e-3 + 1e-3j]))


def test_xarray_result_carries_units_and_cf_flags(fixture_table):
    xr = pytest.importorskip("xarray")
    t = railtab.Table.load(fixture_table)
    ds = t.query("left", y=np.linspace(-0.01, 0.01, 7), xi=0.002)
    assert isinstance(ds, xr.Dataset)
    assert ds["fx"].dims == ("state", "slot") and ds["fx"].attrs["units"] == "N"
    assert ds["y"].attrs["units"] == "m" and ds["max_pressure"].attrs["units"] == "Pa"
    assert ds["status"].attrs["flag_meanings"].split()[:2] == ["converged", "not_converged"]
    assert list(ds["status"].attrs["flag_masks"][:3]) == [1, 2, 4]
    assert ds["part_status"].dims == ("state", "slot", "part")
    assert list(ds["part"].values) == ["geometry", "normal", "creep", "wear"]
    plain = t.query("left", y=np.linspace(-0.01, 0.01, 7), xi=0.002, as_xarray=False)
    np.testing.assert_array_equal(ds["fx"].values, plain["fx"])


def test_status_names_match_the_core():
    assert railtab.status_names(0) == []
    assert railtab.decode_status(0) == "none"
    assert railtab.decode_status(1 | 4 | 1024) == "converged,two_point,out_of_range"
    assert railtab.decode_status(1 << 13) == "failed"
    assert [m for _, m in railtab.STATUS_FLAGS] == [1 << i for i in range(19)]
    assert railtab.decode_status((1 << 16) | (1 << 17)) == "near_equal_minima,curvature_step"
    assert railtab.decode_status(1 << 18) == "low_confidence"
    assert railtab.decode_status(1 << 14 | 1 << 15) == "area_too_small,not_planar"


def test_query_on_a_generated_table(stripes_table):
    t = railtab.Table.load(stripes_table)
    assert t.scene_name == "default_stripes"
    y = np.linspace(-0.005, 0.005, 11)
    r = t.query("left", y=y, load=78.5e3, xi=0.0, as_xarray=False)
    # the tread carries the load near the centre; N cos(angle) ~ the wheel load
    n = r["normal_force"][:, 0] + r["normal_force"][:, 1]
    assert (n > 0.9 * 78.5e3).all() and (n < 1.2 * 78.5e3).all()
    assert (railtab.has_flag(r["status"][:, 0], "converged")).all()


def test_roll_on_an_equilibrium_roll_table_is_flagged(stripes_table):
    # The STRIPES table's roll follows the kinematic equilibrium: roll is not an input. A query
    # that gives one is answered at the equilibrium and flagged out_of_range, never silently.
    t = railtab.Table.load(stripes_table)
    assert "roll" not in t.axes and "roll" not in t.fixed_axes
    plain = t.query("left", y=0.003, load=78.5e3, as_xarray=False)
    rolled = t.query("left", y=0.003, load=78.5e3, roll=[0.0, 0.002], as_xarray=False)
    assert not railtab.has_flag(plain["status"], "out_of_range").any()
    assert list(railtab.has_flag(rolled["status"][:, 0], "out_of_range")) == [False, True]
    np.testing.assert_array_equal(rolled["fx"][1], plain["fx"])
    nan = t.query("left", y=0.003, load=78.5e3, roll=np.nan, as_xarray=False)
    assert railtab.has_flag(nan["status"], "invalid_input").all()


def test_yaw_on_a_table_without_yaw_is_flagged(stripes_table):
    # The STRIPES table has no yaw: it was computed at yaw 0. A query with another yaw is
    # answered at yaw 0 and flagged out_of_range, never silently (docs/lookup.md, "Yaw").
    t = railtab.Table.load(stripes_table)
    assert "yaw" not in t.axes and "yaw" not in t.fixed_axes and not t.yaw_even
    plain = t.query("left", y=0.003, load=78.5e3, as_xarray=False)
    yawed = t.query("left", y=0.003, load=78.5e3, yaw=[0.0, 0.004], as_xarray=False)
    assert list(railtab.has_flag(yawed["status"][:, 0], "out_of_range")) == [False, True]
    np.testing.assert_array_equal(yawed["fx"][1], plain["fx"])


def test_yaw_axis_from_python(tmp_path, railtab_program):
    # A table of a scene with a yaw axis: Table.query(yaw=...) interpolates it, yaw must be given
    # (an axis), and the yaw = 0 node is railtab.evaluate's state at yaw 0. The symmetric list is
    # stored as its non-negative half and read at |yaw| (docs/table-format.md, yaw_symmetry).
    text = (SOURCE_DIR / "tables" / "default_stripes.toml").read_text()
    scene = tmp_path / "yaw.toml"
    scene.write_text(text[:text.index("[grid]")] + "[grid]\ny = [0.0, 0.004, 0.008]\nequilibrium_roll = true\n"
                     "yaw = [-0.01, 0.0, 0.01]\nload = 78.5e3\n")
    table = tmp_path / "yaw.h5"
    subprocess.run([railtab_program, "generate", str(scene), "-o", str(table), "--threads", "2"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t = railtab.Table.load(table)
    assert t.format_version == "2.4" and list(t.axes["yaw"]) == [0.0, 0.01] and t.yaw_even
    with pytest.raises(TypeError, match="yaw is an axis"):
        t.query("left", y=0.004)
    r = t.query("left", y=0.008, yaw=[-0.01, 0.0, 0.005, 0.01], as_xarray=False)
    assert not railtab.has_flag(r["status"], "out_of_range").any()
    direct = railtab.evaluate(str(scene), 0.008, yaw=0.0)
    n0 = sum(c["normal_force"] for c in direct["wheels"][0]["contacts"])
    assert r["normal_force"][1].sum() == pytest.approx(n0, rel=2e-6)  # the creep part: float32 (format 2.2)
    flange = r["contact_angle"][:, 1]
    assert flange[1] != flange[3]  # the flange contact moves with yaw (at second order: +-yaw give one angle)
    assert flange[2] == pytest.approx(0.5 * (flange[1] + flange[3]), rel=1e-12)  # linear between nodes
    for name in ("normal_force", "contact_angle", "fx", "status"):
        np.testing.assert_array_equal(r[name][0], r[name][3])  # -yaw reads +yaw's values
    # A list that is not symmetric ([0, 0.01]) is stored whole: not even, -yaw is outside its axis.
    scene.write_text(scene.read_text().replace("yaw = [-0.01, 0.0, 0.01]", "yaw = [0.0, 0.01]"))
    whole = tmp_path / "yaw_whole.h5"
    subprocess.run([railtab_program, "generate", str(scene), "-o", str(whole), "--threads", "2"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    w = railtab.Table.load(whole)
    assert list(w.axes["yaw"]) == [0.0, 0.01] and not w.yaw_even
    rw = w.query("left", y=0.008, yaw=[-0.01, 0.01], as_xarray=False)
    assert list(railtab.has_flag(rw["status"][:, 1], "out_of_range")) == [True, False]


# The low_confidence bit on the STRIPES table (docs/lookup.md, "Low confidence").


def low(status):
    """Where the low_confidence bit is set (docs/lookup.md, "Low confidence")."""
    return railtab.has_flag(status, "low_confidence")


def test_flange_state_past_the_point_jump_is_flagged(stripes_table):
    table = railtab.Table.load(stripes_table)
    # Left wheel, y = 6.3 mm: the table gives N = 129 kN, fy = 0.75 kN where the model gives
    # 181 kN and 16.9 kN (the loaded patch lags the rigid point that jumped up the flange at
    # 6.2515 mm); nothing flagged it before.
    r = table.query("left", y=0.0063, load=78.5e3, xi=2e-4, eta=1e-3, phi=-0.2, as_xarray=False)
    loaded = r["normal_force"] > 0
    assert loaded.any()
    assert low(r["status"][loaded]).all(), railtab.decode_status(r["status"])
    # The mirror state of the right wheel too.
    m = table.query("right", y=-0.0063, load=78.5e3, xi=2e-4, eta=1e-3, phi=-0.2, as_xarray=False)
    assert low(m["status"][m["normal_force"] > 0]).all()


def test_clean_tread_states_are_not_flagged(stripes_table):
    table = railtab.Table.load(stripes_table)
    y = np.linspace(-0.004, 0.004, 17)
    r = table.query("left", y=y, load=78.5e3, xi=1e-3, eta=-1e-3, phi=0.1, as_xarray=False)
    assert not low(r["status"]).any(), railtab.decode_status(r["status"])


def test_hand_over_keeps_the_whole_load(stripes_table):
    table = railtab.Table.load(stripes_table)
    # Through the tread-to-flange hand-over (5.58 .. 5.61 mm at 78.5 kN) the loaded patch moves
    # from slot 0 to slot 1 before its rigid point does. Summed over the slots that carry a force
    # (skipping by force, not by status), the vertical load stays the wheel's.
    y = np.linspace(0.0055, 0.0061, 601)                  # 1 um steps
    for load in (60e3, 78.5e3, 100e3):                    # the load nodes: each its own hand-over
        r = table.query("left", y=y, load=load, as_xarray=False)
        n = r["normal_force"]
        angle = r["contact_angle"]
        unpaired = (n > 0) & (r["rolling_radius"] == 0)   # the patch's rigid point is in the other slot
        angle = np.where(unpaired, angle[:, ::-1], angle)
        vertical = (np.where(n > 0, n, 0.0) * np.cos(angle)).sum(axis=1)
        assert np.abs(vertical / load - 1).max() < 0.08, (load, np.abs(vertical / load - 1).max())
        total = n.sum(axis=1)
        assert np.abs(np.diff(total)).max() < 0.02 * load  # continuous: no step of a dropped contact
        # The unpaired slots are the ones a loop skipping non-converged slots drops: flagged.
        assert unpaired.any() and low(r["status"][unpaired]).all(), load
        dropped = ~railtab.has_flag(r["status"], "converged").any(axis=1)
        assert dropped.any()                              # what the old loop lost: still there


def test_flagged_states_are_a_small_fraction(stripes_table):
    table = railtab.Table.load(stripes_table)
    rng = np.random.default_rng(32)
    n = 20000
    axes = table.axes
    wheel = rng.integers(0, 2, n)
    state = {name: rng.uniform(axes[name][0], axes[name][-1], n) for name in ("y", "load", "xi", "eta", "phi")}
    r = table.query(wheel, **state, as_xarray=False)
    flagged = low(r["status"]).any(axis=1)
    fraction = flagged.mean()
    print(f"[ info ] low_confidence on {fraction:.2%} of {n} random states of the STRIPES table")
    assert 0 < fraction <= 0.02
