# SPDX-License-Identifier: Apache-2.0
"""railtab.Table: loading, vectorised queries against the fixture's known values, units, status."""
import numpy as np
import pytest

import railtab
from conftest import fixture_value

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
    assert [m for _, m in railtab.STATUS_FLAGS] == [1 << i for i in range(18)]
    assert railtab.decode_status((1 << 16) | (1 << 17)) == "near_equal_minima,curvature_step"
    assert railtab.decode_status(1 << 14 | 1 << 15) == "area_too_small,not_planar"


def test_query_on_a_generated_table(default_table):
    t = railtab.Table.load(default_table)
    assert t.scene_name == "default"
    y = np.linspace(-0.005, 0.005, 11)
    r = t.query("left", y=y, load=78.5e3, xi=0.0, as_xarray=False)
    # the tread carries the load near the centre; N cos(angle) ~ the wheel load
    n = r["normal_force"][:, 0] + r["normal_force"][:, 1]
    assert (n > 0.9 * 78.5e3).all() and (n < 1.2 * 78.5e3).all()
    assert (railtab.has_flag(r["status"][:, 0], "converged")).all()
