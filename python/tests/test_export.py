# SPDX-License-Identifier: Apache-2.0
"""`railtab export TABLE --csv`: the physical creep forces on the table's nodes (docs/lookup.md,
"Export to CSV"). The CSV's values equal lookup queries at the rows' states; on the STRIPES table
(normalised creep coordinates) the rows' creepages span the scene's ranges and the rows agree with
the direct model at the same state; bad inputs exit 1 naming the input."""
import csv
import subprocess
import tomllib

import numpy as np
import pytest

import railtab
from conftest import SOURCE_DIR

SCENE = SOURCE_DIR / "tables" / "default_stripes.toml"
COLUMNS = ["wheel", "y_m", "roll_rad", "load_N", "xi", "eta", "phi_rad_per_m", "slot", "fx_N", "fy_N", "mz_Nm",
           "normal_force_N", "contact_angle_rad", "track_lateral_N", "track_vertical_N", "status", "status_names"]


def run(program, *args):
    return subprocess.run([program, *map(str, args)], capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def exported(railtab_program, stripes_table, tmp_path_factory):
    out = tmp_path_factory.mktemp("export") / "stripes.csv"
    r = run(railtab_program, "export", stripes_table, "--csv", "-o", out)
    assert r.returncode == 0, r.stderr
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    cols = {name: [row[k] for row in body] for k, name in enumerate(header)}
    num = {name: np.array(v, dtype=float) for name, v in cols.items() if name not in ("wheel", "status_names")}
    return header, cols, num


def test_header_and_one_row_per_node_and_slot(exported, stripes_table):
    header, cols, num = exported
    assert header == COLUMNS
    grid = tomllib.loads(SCENE.read_text())["grid"]
    table = railtab.Table.load(stripes_table)
    nodes = len(table.axes["y"]) * len(grid["load"]) * len(grid["xi"]) * len(grid["eta"]) * len(grid["phi"])
    assert len(cols["wheel"]) == 2 * table.n_slots * nodes
    assert cols["wheel"].count("left") == table.n_slots * nodes
    # Physical creepages: each slot's nodes span the scene's range, its ends exactly.
    for name, key in (("xi", "xi"), ("eta", "eta"), ("phi_rad_per_m", "phi")):
        assert num[name].min() == grid[key][0] and num[name].max() == grid[key][-1], name
        per_node = len(np.unique(num[name][(num["slot"] == 0) & (num["y_m"] == 0.0) & (num["load_N"] == 78.5e3)]))
        assert per_node == len(grid[key]), name


def test_values_equal_lookup_queries_at_the_rows_states(exported, stripes_table):
    _, cols, num = exported
    table = railtab.Table.load(stripes_table)
    wheel = np.array(cols["wheel"])
    res = table.query(wheel, y=num["y_m"], load=num["load_N"], xi=num["xi"], eta=num["eta"],
                      phi=num["phi_rad_per_m"], track_forces=True, as_xarray=False)
    slot = num["slot"].astype(int)
    pick = lambda a: a[np.arange(slot.size), slot]  # noqa: E731
    for column, output in (("fx_N", "fx"), ("fy_N", "fy"), ("mz_Nm", "mz"), ("normal_force_N", "normal_force"),
                           ("contact_angle_rad", "contact_angle"), ("track_lateral_N", "track_lateral_force"),
                           ("track_vertical_N", "track_vertical_force")):
        np.testing.assert_array_equal(num[column], pick(res[output]), err_msg=column)
    # The forces are physical (N), not the stored residuals F / (mu N) - law: saturated rows reach mu N.
    loaded = num["normal_force_N"] > 0
    ratio = np.hypot(num["fx_N"], num["fy_N"])[loaded] / (0.3 * num["normal_force_N"][loaded])
    assert ratio.max() > 0.9 and ratio.max() < 1.05, ratio.max()
    assert (num["status"].astype(np.uint32) & 1).any()  # converged nodes
    assert all("," not in names for names in cols["status_names"])


def test_rows_agree_with_the_direct_model(exported):
    """Tread rows (one contact) at nonzero creepage: the direct model at the row's state gives the
    same forces to the table's storage precision (float32, 20 bits)."""
    _, cols, num = exported
    rng = np.random.default_rng(5)
    candidates = np.flatnonzero((np.abs(num["y_m"]) <= 0.003) & (num["slot"] == 0) & (num["normal_force_N"] > 0)
                                & (num["xi"] != 0) & (num["eta"] != 0))
    scene = railtab.Scene.load(SCENE)
    for k in rng.choice(candidates, 6, replace=False):
        direct = railtab.evaluate(scene, y=num["y_m"][k], load=num["load_N"][k],
                                  creepage=(num["xi"][k], num["eta"][k], num["phi_rad_per_m"][k]))
        contacts = direct["wheels"][0 if cols["wheel"][k] == "left" else 1]["contacts"]
        assert len(contacts) == 1, (k, contacts)
        mun = 0.3 * contacts[0]["normal_force"]
        for column, key in (("fx_N", "fx"), ("fy_N", "fy"), ("normal_force_N", "normal_force")):
            assert abs(num[column][k] - contacts[0][key]) < 1e-4 * mun, (column, k, num[column][k], contacts[0][key])


def test_stdout_without_output(railtab_program, stripes_table):
    r = run(railtab_program, "export", stripes_table, "--csv")
    assert r.returncode == 0 and r.stdout.startswith(",".join(COLUMNS) + "\n"), r.stderr


@pytest.mark.parametrize("case", ["missing", "unwritable", "no_csv", "input_as_output"])
def test_bad_inputs(railtab_program, stripes_table, tmp_path, case):
    if case == "missing":
        missing = tmp_path / "no-such-table.h5"
        r = run(railtab_program, "export", missing, "--csv", "-o", tmp_path / "out.csv")
        assert r.returncode == 1 and str(missing) in r.stderr, r.stderr
        assert list(tmp_path.iterdir()) == []
    elif case == "unwritable":
        target = "/proc/railtab-not-writable/out.csv"
        r = run(railtab_program, "export", stripes_table, "--csv", "-o", target)
        assert r.returncode == 1 and target in r.stderr and "refused before starting" in r.stderr, r.stderr
    elif case == "no_csv":
        r = run(railtab_program, "export", stripes_table)
        assert r.returncode == 2 and "--csv" in r.stderr, r.stderr
    else:
        before = stripes_table.read_bytes()
        r = run(railtab_program, "export", stripes_table, "--csv", "-o", stripes_table)
        assert r.returncode == 1 and str(stripes_table) in r.stderr, r.stderr
        assert stripes_table.read_bytes() == before
