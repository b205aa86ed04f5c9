# SPDX-License-Identifier: Apache-2.0
"""Format 2.0 tables are self-describing (docs/table-format.md): xarray opens every group with
its coordinates and units, the h5py example of the docs runs as written, attributes are typed,
status bits are explained by CF attributes, and SOURCE_DATE_EPOCH makes rebuilds byte-identical."""
import contextlib
import io
import json
import os
import re
import subprocess

import numpy as np
import pytest

from conftest import SOURCE_DIR

h5py = pytest.importorskip("h5py")

GROUPS = [f"{w}/{p}" for w in ("left", "right") for p in ("geometry", "normal", "creep", "wear")]
UNITS = {"fx": "N", "max_pressure": "Pa", "contact_angle": "rad", "wear_rate": "m2/m", "area": "m2"}


def text(value):
    """A string attribute as h5py returns it: fixed-length strings (the format's integrity: their
    bytes live in the checksummed object header) come back as bytes, arrays of them as S arrays."""
    if isinstance(value, np.ndarray):
        return [text(v) for v in value]
    assert isinstance(value, bytes), f"expected a fixed-length string attribute, got {value!r}"
    return value.decode()


@pytest.mark.parametrize("engine", ["h5netcdf", "netcdf4"])
def test_xarray_opens_every_group_with_coordinates_and_units(stripes_table, engine):
    xr = pytest.importorskip("xarray")
    pytest.importorskip(engine if engine == "h5netcdf" else "netCDF4")
    for group in GROUPS:
        ds = xr.open_dataset(stripes_table, group=group, engine=engine)
        for dim in ds.dims:
            assert dim in ds.coords, f"{group}: dimension {dim} without coordinate"
            assert "units" in ds.coords[dim].attrs
        for name, units in UNITS.items():
            if name in ds:
                assert ds[name].attrs["units"] == units
        assert ds["status"].attrs["flag_meanings"].split()[0] == "converged"
        ds.close()
    creep = xr.open_dataset(stripes_table, group="left/creep", engine=engine)
    with h5py.File(stripes_table) as f:
        np.testing.assert_array_equal(creep["y"].values, f["axes/y"][()])
        # The STRIPES table's creep part is normalised (format 2.1): fx / (mu N) minus the saturation
        # law over the coordinate v_xi in [-1, 1] (docs/table-format.md, "Normalised creep part").
        curve = creep.fx_normalised.sel(y=0.003, load=78.5e3, eta=0, phi=0, slot=0, method="nearest")
        iy = int(np.abs(f["axes/y"][()] - 0.003).argmin())
        np.testing.assert_array_equal(curve.values, f["left/creep/fx_normalised"][iy, 1, :, 2, 1, 0])
    assert creep["xi"].values[0] == -1.0 and creep["xi"].values[-1] == 1.0
    assert np.all(np.abs(curve.values) < 0.5)   # the law carries the saturating curve, the table the rest
    # roll follows the equilibrium: roll(y) is a coordinate of the group, equal to /equilibrium_roll
    assert "roll" in creep.coords and creep.coords["roll"].dims == ("y",)
    assert creep.coords["roll"].attrs["units"] == "rad"
    with h5py.File(stripes_table) as f:
        np.testing.assert_array_equal(creep.coords["roll"].values, f["equilibrium_roll"][()])
    creep.close()


def test_typed_attributes_and_status_flags(stripes_table):
    with h5py.File(stripes_table) as f:
        assert text(f.attrs["format_version"]) == "2.3"
        assert "fixed_axes" not in f.attrs and "models" not in f.attrs   # no JSON strings
        models = f["models"].attrs
        assert text(models["normal"]) == "stripes-ab" and models["strips"] == 50
        assert isinstance(models["friction"], float) and models["friction"] == 0.3
        assert text(f.attrs["roll_mode"]) == "equilibrium"
        slot = f["axes/slot"]
        assert text(slot.attrs["slot_names"]) == ["tread", "flange"]
        assert text(slot.attrs["flag_meanings"]) == "tread flange"
        for group in GROUPS:
            st = f[group]["status"]
            masks, names = st.attrs["flag_masks"], text(st.attrs["flag_meanings"]).split()
            assert st.attrs["flag_masks"].dtype == np.uint32 and len(masks) == len(names) >= 14
            assert dict(zip(names, masks))["out_of_range"] == 1024
            # every bit set anywhere in the file is explained
            assert np.all(np.bitwise_and(st[()], ~np.bitwise_or.reduce(masks)) == 0)


def test_h5py_example_of_the_docs_runs_as_written(stripes_table, tmp_path):
    text = (SOURCE_DIR / "docs" / "table-format.md").read_text()
    code = re.search(r"<!-- h5py-example -->\s*```python\n(.*?)```", text, re.S).group(1)
    (tmp_path / "default.h5").symlink_to(stripes_table)
    old = os.getcwd()
    os.chdir(tmp_path)
    out = io.StringIO()
    try:
        with contextlib.redirect_stdout(out):
            exec(compile(code, "docs/table-format.md example", "exec"), {})
    finally:
        os.chdir(old)
    lines = out.getvalue().splitlines()
    assert lines[0].startswith("y,load,xi,eta,phi,slot 1")   # fx_normalised: F / (mu N) - law
    assert "equilibrium stripes-ab" in lines[1]
    assert " N at xi = " in lines[2]
    assert float(lines[2].split()[0]) < 0                                # braking at xi > 0
    assert "converged" in lines[3]


def test_fixed_variables_are_scalar_datasets(railtab_program, tmp_path):
    scene = (SOURCE_DIR / "tables" / "default_stripes.toml").read_text()
    scene = scene.replace("load = [60e3, 78.5e3, 100e3]", "load = [78.5e3]")
    scene = re.sub(r"y = \[\n.*?\n\]", "y = [{ start = -0.004, stop = 0.004, step = 0.002 }]", scene, flags=re.S)
    (tmp_path / "s.toml").write_text(scene)
    subprocess.run([railtab_program, "generate", str(tmp_path / "s.toml"), "-o", str(tmp_path / "s.h5"),
                    "--quiet"], check=True)
    with h5py.File(tmp_path / "s.h5") as f:
        assert f["axes/load"].shape == () and f["axes/load"][()] == 78.5e3
        assert text(f["axes/load"].attrs["units"]) == "N"
        assert text(f["left/normal/area"].attrs["coordinates"]) == "load roll"   # roll(y): equilibrium
    xr = pytest.importorskip("xarray")
    ds = xr.open_dataset(tmp_path / "s.h5", group="left/normal", engine="h5netcdf")
    assert float(ds["load"]) == 78.5e3 and "load" in ds.coords


def test_source_date_epoch_gives_identical_bytes(railtab_program, tmp_path):
    env = dict(os.environ, SOURCE_DATE_EPOCH="1700000000")
    # The STRIPES scene on a 21-node y grid: every part of a table (sweep, contact jumps and their
    # one-sided values, error map), in a third of the STRIPES table's time.
    scene_text = (SOURCE_DIR / "tables" / "default_stripes.toml").read_text()
    scene_text = re.sub(r"y = \[\n.*?\n\]", "y = { start = -0.010, stop = 0.010, step = 0.001 }", scene_text,
                        flags=re.S)
    scene = tmp_path / "scene.toml"
    scene.write_text(scene_text)
    for name, threads in (("a.h5", "1"), ("b.h5", "2")):
        subprocess.run([railtab_program, "generate", str(scene), "-o", str(tmp_path / name), "--threads", threads,
                        "--quiet"], check=True, env=env)
    assert (tmp_path / "a.h5").read_bytes() == (tmp_path / "b.h5").read_bytes()
    with h5py.File(tmp_path / "a.h5") as f:
        assert text(f.attrs["created"]) == "2023-11-14T22:13:20Z"
    bad = dict(os.environ, SOURCE_DATE_EPOCH="yesterday")
    r = subprocess.run([railtab_program, "generate", str(scene), "-o", str(tmp_path / "c.h5"), "--quiet"], env=bad,
                       capture_output=True, text=True)
    assert r.returncode != 0 and "SOURCE_DATE_EPOCH" in r.stderr
    assert not (tmp_path / "c.h5").exists()


def test_exact_default_scene_gives_identical_bytes_for_one_and_two_threads(railtab_program, tmp_path):
    # The exact default (tables/default.toml, Kalker's half-space model) cropped to the cell where
    # the rigid point jumps up the flange (y 6.2 to 6.3 mm: 6 contact jumps over both wheels and
    # loads) and the ends of each creepage range: its sweep, jumps, one-sided values and error map
    # in about 4 s of CPU a run instead of the full table's minutes.
    env = dict(os.environ, SOURCE_DATE_EPOCH="1700000000")
    scene_text = (SOURCE_DIR / "tables" / "default.toml").read_text()
    assert 'normal_model = "halfspace"' in scene_text
    scene_text = re.sub(r"y = \[\n.*?\n\]", "y = [0.0062, 0.0063]", scene_text, flags=re.S)
    for axis, end in (("xi", 0.004), ("eta", 0.004), ("phi", 0.3)):
        scene_text = re.sub(rf"^{axis} = \[.*\]$", f"{axis} = [{-end}, {end}]", scene_text, flags=re.M)
    scene = tmp_path / "scene.toml"
    scene.write_text(scene_text)
    for name, threads in (("a.h5", "1"), ("b.h5", "2")):
        subprocess.run([railtab_program, "generate", str(scene), "-o", str(tmp_path / name), "--threads", threads,
                        "--quiet"], check=True, env=env)
    with h5py.File(tmp_path / "a.h5") as f:
        assert text(f.attrs["scene_name"]) == "default"
        assert np.isfinite(f["jumps/left_y"][()]).sum() > 0        # the cell's jumps and their sides are in it
    assert (tmp_path / "a.h5").read_bytes() == (tmp_path / "b.h5").read_bytes()


def test_query_command_agrees_with_the_module_and_the_file(railtab_program, stripes_table):
    import railtab

    out = subprocess.run([railtab_program, "query", str(stripes_table), "--y", "0.003,-0.0042", "--load", "78500",
                          "--creepage", "0.001,0,0", "--json"], check=True, capture_output=True, text=True)
    j = json.loads(out.stdout)
    assert [q["wheel"] for q in j["queries"]] == ["left", "right", "left", "right"]
    t = railtab.Table.load(stripes_table)
    r = t.query(["left", "right", "left", "right"], y=[0.003, 0.003, -0.0042, -0.0042], load=78500.0, xi=0.001,
                as_xarray=False)
    for k, q in enumerate(j["queries"]):
        for slot, c in enumerate(q["contacts"]):
            assert c["fx"] == r["fx"][k, slot] and c["normal_force"] == r["normal_force"][k, slot]
            assert c["status"] == railtab.decode_status(r["status"][k, slot])
    with h5py.File(stripes_table) as f:
        for name, units in j["units"].items():
            if "creep_map" in f.attrs and name in ("fx", "fy", "mz"):
                continue  # stored normalised (format 2.1): fx_normalised etc., units 1 and m
            part = next(p for p in ("geometry", "normal", "creep", "wear") if name in f["left"][p])
            assert text(f["left"][part][name].attrs["units"]) == units, name


def test_inspect_json_describes_the_file(railtab_program, stripes_table):
    out = subprocess.run([railtab_program, "inspect", str(stripes_table), "--json"], check=True,
                         capture_output=True, text=True)
    j = json.loads(out.stdout)
    assert j["attributes"]["format_version"] == "2.3"
    assert j["checksums_verified"] is True                             # format 2 always carries them
    assert j["attributes"]["models"]["normal"] == "stripes-ab"        # an object, not JSON text
    assert j["attributes"]["fixed_axes"] == {"roll": "equilibrium"}
    with h5py.File(stripes_table) as f:
        assert {a["name"]: a["size"] for a in j["axes"]} == {k: f["axes"][k].size for k in f["axes"]}
        group = next(g for g in j["groups"] if g["path"] == "/left/creep")
        status = next(d for d in group["datasets"] if d["name"] == "status")
        bits = f["left/creep/status"][()]
        assert status["shape"] == list(bits.shape)
        assert status["status_counts"]["no_contact"] == int((bits == 0).sum())
        assert status["status_counts"]["converged"] == int((bits & 1).astype(bool).sum())


def test_error_map_is_stored_and_served(stripes_table, fixture_table):
    """The STRIPES table's error map (format 2.3): every dataset has units, the lookup serves the
    stored region of a query, and a table without a map (the format-2.0 fixture) gives None."""
    import railtab
    with h5py.File(stripes_table) as f:
        sampling = json.loads(text(f.attrs["error_map_sampling"]))
        assert sampling["model_vs_exact"] == "halfspace"
        g = f["error_map"]
        start, end = g["y_band_start"][()], g["y_band_end"][()]
        for comparison in ("table_vs_model", "model_vs_exact"):
            for name, d in g[comparison].items():
                if name in ("band", "slot"):
                    continue
                assert text(d.attrs["units"]) in ("% of mu N", "% of mu N c", "%", "rad", "1"), name
        fy_max = g["table_vs_model/fy_max"][()]
        samples = g["table_vs_model/samples"][()]
    t = railtab.Table(stripes_table)
    assert t.has_error_map
    b = len(start) // 2
    e = t.error_estimate(0.5 * (start[b] + end[b]), 0)
    assert e["y_band"] == (start[b], end[b])
    assert e["table_vs_model"]["samples"] == samples[b, 0] > 0
    assert e["table_vs_model"]["fy_max"] == fy_max[b, 0]
    assert isinstance(e["model_vs_exact"], dict)
    assert t.error_estimate(end[-1] + 0.01, 0) is None
    old = railtab.Table(fixture_table)
    assert not old.has_error_map and old.error_estimate(0.0, 0) is None
