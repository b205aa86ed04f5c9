# SPDX-License-Identifier: Apache-2.0
"""Table.query(..., derivatives=True) and `railtab query --derivatives --json`: the exact partial
derivatives of the interpolant (docs/lookup.md, "Derivatives"), from Python and the command line."""
import json
import subprocess

import numpy as np
import pytest

import railtab
from conftest import fixture_value


def test_derivatives_of_the_fixture(fixture_table):
    """The fixture is f = c (100 s y + sin(30 xi) + eta^2 / 2 + phi / 10): the linear interpolant's
    derivative in y is exactly 100 s c (affine in y), in phi 0.1 c; in xi it is the cell's secant."""
    table = railtab.Table.load(fixture_table)
    xi = np.array([-0.0031, 0.0004, 0.0052])
    res = table.query("right", y=0.0013, xi=xi, eta=0.0011, phi=0.2, derivatives=True, as_xarray=False)
    c = (1.0 + 2 + 0.1 * 0 + 0)  # creep part (2), fx (0), tread slot
    np.testing.assert_allclose(res["d_fx_d_y"][:, 0], -100.0 * c, rtol=1e-9)
    np.testing.assert_allclose(res["d_fx_d_phi"][:, 0], 0.1 * c, rtol=1e-9)
    nodes = table.axes["xi"]
    i = np.searchsorted(nodes, xi) - 1
    secant = (fixture_value(1, 2, 0, 0, 0.0, xi=nodes[i + 1]) - fixture_value(1, 2, 0, 0, 0.0, xi=nodes[i])) / (
        nodes[i + 1] - nodes[i])
    np.testing.assert_allclose(res["d_fx_d_xi"][:, 0], secant, rtol=1e-9)
    assert res.units["d_fx_d_y"] == "N/m"
    assert res.units["d_fx_d_xi"] == "N"
    assert res.units["d_mz_d_phi"] == "N m/(rad/m)"
    assert "d_fx_d_load" not in res  # load is not an axis of the fixture
    assert res["d_fx_d_y"].shape == (3, table.n_slots)


def test_derivatives_match_central_differences_on_the_stripes_table(stripes_table):
    """Normalised creep coordinates: d fx / d xi and d fy / d y against central differences of the
    same query, cubic, both slots."""
    table = railtab.Table.load(stripes_table, method="cubic")
    y = np.array([-0.0021, 0.0013, 0.0047])
    state = dict(load=81e3, xi=0.0007, eta=-0.0004, phi=0.03)
    res = table.query("left", y=y, derivatives=True, as_xarray=False, **state)
    for axis, h in (("xi", 1e-9), ("y", 1e-8)):
        plus = dict(state, y=y)
        minus = dict(state, y=y)
        plus[axis] = plus[axis] + h
        minus[axis] = minus[axis] - h
        for name in ("fx", "fy", "normal_force"):
            fd = (table.query("left", **plus, as_xarray=False)[name]
                  - table.query("left", **minus, as_xarray=False)[name]) / (2 * h)
            np.testing.assert_allclose(res[f"d_{name}_d_{axis}"], fd, rtol=1e-5, atol=1e-6 * np.abs(fd).max())


def test_one_slot_and_xarray(stripes_table):
    table = railtab.Table.load(stripes_table)
    both = table.query("left", y=0.004, load=78.5e3, xi=0.001, derivatives=True, as_xarray=False)
    one = table.query("left", y=0.004, load=78.5e3, xi=0.001, slot=1, derivatives=True, as_xarray=False)
    assert one["d_fy_d_y"].shape == (1,)
    assert one["d_fy_d_y"][0] == both["d_fy_d_y"][1]
    assert both["d_fx_d_xi"][0] < 0  # fx = -G c^2 C11 xi at small creepage (docs/conventions.md)
    pytest.importorskip("xarray")
    ds = table.query("left", y=[0.001, 0.002], load=78.5e3, derivatives=True)
    assert ds["d_fx_d_xi"].attrs["units"] == "N"
    assert ds["d_fx_d_load"].dims == ("state", "slot")


def test_monotone_cubic_is_refused(fixture_table):
    table = railtab.Table.load(fixture_table, method="monotone-cubic")
    with pytest.raises(ValueError, match="monotone-cubic"):
        table.query("left", y=0.0, derivatives=True)


def test_cli_derivatives_json(stripes_table, railtab_program):
    out = subprocess.run([railtab_program, "query", str(stripes_table), "--y", "0.003", "--load", "78500",
                          "--creepage", "0.001,0,0", "--wheel", "left", "--derivatives", "--json"],
                         check=True, capture_output=True, text=True).stdout
    contact = json.loads(out)["queries"][0]["contacts"][0]
    d = contact["derivatives"]
    assert set(d["fx"]) == {"y", "load", "xi", "eta", "phi"}
    table = railtab.Table.load(stripes_table)
    res = table.query("left", y=0.003, load=78500, xi=0.001, derivatives=True, as_xarray=False)
    assert d["fx"]["xi"] == pytest.approx(res["d_fx_d_xi"][0], rel=1e-12)
    assert d["contact_angle"]["y"] == pytest.approx(res["d_contact_angle_d_y"][0], rel=1e-12)
    bad = subprocess.run([railtab_program, "query", str(stripes_table), "--y", "0.003", "--load", "78500",
                          "--method", "monotone-cubic", "--derivatives"], capture_output=True, text=True)
    assert bad.returncode != 0
    assert "--derivatives needs --method linear or cubic" in bad.stderr
