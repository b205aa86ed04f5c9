# SPDX-License-Identifier: Apache-2.0
"""Table.query(..., track_forces=True): the forces of the rail on the wheel in track axes and Y/Q
(docs/conventions.md, "Track-frame forces and Y/Q") against the same rotation computed here from
the query's raw outputs (normal_force, fy, contact_angle per slot), on flange states of the STRIPES
table, both wheels."""
import numpy as np
import pytest

import railtab


def by_hand(res, wheel):
    """Per slot: N along n = (0, -sin g, cos g), fy along s = (0, cos g, sin g); a loaded slot without
    its rigid point (rolling radius 0) takes the other slot's angle. Y = -sigma sum lateral, Q = sum vertical."""
    n, fy, g, r = (np.asarray(res[k], dtype=float) for k in ("normal_force", "fy", "contact_angle", "rolling_radius"))
    g = np.where((r > 0) | (r[..., ::-1] <= 0), g, g[..., ::-1])  # two slots: the other is [..., ::-1]
    loaded = n > 0
    lateral = np.where(loaded, -n * np.sin(g) + fy * np.cos(g), 0.0)
    vertical = np.where(loaded, n * np.cos(g) + fy * np.sin(g), 0.0)
    sigma = 1.0 if wheel == "left" else -1.0
    y_force = -sigma * lateral.sum(-1)
    q_force = vertical.sum(-1)
    return lateral, vertical, y_force, q_force, y_force / q_force


@pytest.mark.parametrize("wheel, sign", [("left", 1.0), ("right", -1.0)])
def test_y_over_q_of_flange_states_equals_the_rotation_of_the_raw_outputs(stripes_table, wheel, sign):
    table = railtab.Table.load(stripes_table)
    # Tread, the tread-flange hand-over (5.5 .. 6.25 mm: a loaded slot may lack its rigid point) and
    # the flange, with lateral creepage and spin; the right wheel at the mirrored y.
    y = sign * np.array([0.002, 0.0057, 0.0059, 0.007, 0.0085, 0.0095])
    res = table.query(wheel, y=y, load=78.5e3, xi=0.0005, eta=0.001, phi=0.1, track_forces=True, as_xarray=False)
    lateral, vertical, y_force, q_force, y_over_q = by_hand(res, wheel)
    np.testing.assert_allclose(res["track_lateral_force"], lateral, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(res["track_vertical_force"], vertical, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(res["y_force"], y_force, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(res["q_force"], q_force, rtol=1e-12)
    np.testing.assert_allclose(res["y_over_q"], y_over_q, rtol=1e-12)
    np.testing.assert_allclose(res["wheel_lateral_force"], lateral.sum(-1), rtol=1e-12, atol=1e-9)
    # The flange states really are flange contact: the flange slot carries load at a steep angle,
    # and Y/Q is that of a flange (left 3.2, 1.9, 1.6; right, whose eta is not the mirror of the
    # left's, 1.2, 0.88, 0.76), above the tread's.
    flange = np.abs(y) >= 0.007
    assert (res["normal_force"][flange, 1] > 0).all()
    assert (sign * res["contact_angle"][flange, 1] > 0.8).all()  # 1.07, 0.91, 0.83 rad at 7, 8.5, 9.5 mm
    assert (res["y_over_q"][flange] > 0.7).all(), res["y_over_q"]
    assert abs(res["y_over_q"][0]) < 0.35, res["y_over_q"]  # tread: at most mu + tan(g), g ~ 0.04 rad


def test_the_wheels_mirror_and_q_carries_the_load(stripes_table):
    """Left at y and right at -y are mirror images: the same Y, Q and Y/Q. At zero creepage Q is the
    vertical load the slots carry with the table's angles (within the 20 % of the load balance rule,
    docs/lookup.md "Low confidence"; on the tread closely)."""
    table = railtab.Table.load(stripes_table)
    y = np.array([0.0, 0.003, 0.008, 0.0095])
    left = table.query("left", y=y, load=78.5e3, track_forces=True, as_xarray=False)
    right = table.query("right", y=-y, load=78.5e3, track_forces=True, as_xarray=False)
    for key in ("y_force", "q_force", "y_over_q"):
        np.testing.assert_allclose(left[key], right[key], rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(left["wheel_lateral_force"], -right["wheel_lateral_force"], rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(left["q_force"][:2], 78.5e3, rtol=0.01)
    np.testing.assert_allclose(left["q_force"], 78.5e3, rtol=0.2)


def test_track_forces_needs_every_slot_and_names_units(stripes_table):
    table = railtab.Table.load(stripes_table)
    with pytest.raises(ValueError, match="slot"):
        table.query("left", y=0.008, load=78.5e3, slot=1, track_forces=True)
    res = table.query("left", y=[0.0, 0.008], load=78.5e3, track_forces=True, as_xarray=False)
    assert res.units["y_over_q"] == "1" and res.units["track_lateral_force"] == "N"
    assert res["track_lateral_force"].shape == (2, table.n_slots)
    assert res["y_over_q"].shape == (2,)
    xr = pytest.importorskip("xarray")
    ds = table.query("left", y=[0.0, 0.008], load=78.5e3, track_forces=True)
    assert isinstance(ds, xr.Dataset)
    assert ds["y_over_q"].dims == ("state",) and ds["q_force"].attrs["units"] == "N"
