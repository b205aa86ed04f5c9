# SPDX-License-Identifier: Apache-2.0
"""Arguments of the Python module read like the command line's numbers (core/number_input.hpp):
a wheel or slot that is not exactly one of its values, and a path holding a NUL, are refused,
never coerced (wheel=2**32 or 0.7 was the left wheel, slot=1.7 slot 1, a path cut at its NUL)."""
import numpy as np
import pytest

import railtab
from conftest import SOURCE_DIR


@pytest.mark.parametrize("wheel", [2**32, 0.7, -1, 2, float("nan"), [0, 1.5], np.array([1, 2**40])])
def test_wheel_other_than_0_or_1_is_refused(fixture_table, wheel):
    t = railtab.Table.load(fixture_table)
    with pytest.raises(ValueError, match=r"wheel \(0 = left, 1 = right\): must be a whole number in \[0, 1\]"):
        t.query(wheel, y=0.0)


def test_wheel_0_1_and_names_still_work(fixture_table):
    t = railtab.Table.load(fixture_table)
    a = t.query([0, 1, 1.0, np.int64(0)], y=0.001, as_xarray=False)
    b = t.query(["left", "right", "right", "left"], y=0.001, as_xarray=False)
    np.testing.assert_array_equal(a["rolling_radius"], b["rolling_radius"])


@pytest.mark.parametrize("slot,words", [(-1, "got -1"), (1.7, "not a whole number"), (2, "got 2"),
                                        (2**64, "got 1.84467e+19"), (float("nan"), "got NaN"),
                                        (float("inf"), "infinity")])
def test_slot_outside_the_table_or_fractional_is_refused(fixture_table, slot, words):
    t = railtab.Table.load(fixture_table)  # two slots
    with pytest.raises(ValueError, match=r"slot: must be a whole number in \[0, 1\]") as e:
        t.query("left", y=0.0, slot=slot)
    assert words in str(e.value)


@pytest.mark.parametrize("slot", ["1", None.__class__, b"1"])
def test_slot_that_is_no_number_is_a_type_error(fixture_table, slot):
    with pytest.raises(TypeError, match="slot must be a number"):
        railtab.Table.load(fixture_table).query("left", y=0.0, slot=slot)


def test_slot_given_as_whole_float_or_numpy_int_works(fixture_table):
    t = railtab.Table.load(fixture_table)
    a = t.query("left", y=0.001, slot=1, as_xarray=False)
    for same in (1.0, np.int32(1), np.float64(1.0)):
        np.testing.assert_array_equal(t.query("left", y=0.001, slot=same, as_xarray=False)["fx"], a["fx"])


def test_path_with_a_nul_is_refused_everywhere(fixture_table, tmp_path):
    scene = SOURCE_DIR / "tables" / "default_stripes.toml"
    rail = SOURCE_DIR / "tests" / "data" / "profiles" / "site_b_hr.prr"
    for call in (lambda: railtab.Table.load(str(fixture_table) + "\0junk"),
                 lambda: railtab.Table.load(str(fixture_table).encode() + b"\0junk"),
                 lambda: railtab.Scene.load(str(scene) + "\0junk"),
                 lambda: railtab.Profile.read(str(rail) + "\0junk", "rail"),
                 lambda: railtab.Profile.s1002().write_simpack(str(tmp_path / "w.prw") + "\0junk")):
        with pytest.raises(ValueError, match="NUL character"):
            call()
    assert list(tmp_path.iterdir()) == []
    # The compiled module refuses it too (a caller bypassing railtab/_table.py).
    with pytest.raises(ValueError, match="NUL character"):
        railtab._railtab.Table.load(str(fixture_table) + "\0junk", "linear")


@pytest.mark.parametrize("kw,name", [({"y": 7.0}, "y"), ({"y": 0.001, "roll": 3.0}, "roll"),
                                     ({"y": 0.001, "load": 1e300}, "load"),
                                     ({"y": 0.001, "mu": 1e300, "creepage": (0.001, 0, 0)}, "mu")])
def test_evaluate_numbers_follow_the_command_line_ranges(kw, name):
    with pytest.raises(railtab.Error, match=rf"^{name}: must be a number in"):
        railtab.evaluate(SOURCE_DIR / "tables" / "default_stripes.toml", **kw)


@pytest.mark.parametrize("step", [0.0, -1e-4, 1e-12, float("nan"), 1.0])
def test_profile_sampling_step_is_checked(step):
    with pytest.raises(ValueError, match=r"step: must be a number in \[1e-06, 0.01\] m"):
        railtab.Profile.s1002().sample(step)
