# SPDX-License-Identifier: Apache-2.0
"""railtab.evaluate: the direct models give exactly what `railtab eval --json` prints."""
import json
import subprocess

import numpy as np
import pytest

import railtab
from conftest import SOURCE_DIR

SCENE = SOURCE_DIR / "tables" / "default_stripes.toml"


def eval_json(program, *args):
    out = subprocess.run([program, "eval", "--scene", str(SCENE), "--json", *args], check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout)


@pytest.mark.parametrize("args,kwargs", [
    (["--y", "0.003", "--load", "78500"], {"y": 0.003, "load": 78500.0}),
    (["--y", "0.008", "--load", "60000", "--creepage", "0.001,-0.002,0.1", "--model", "hertz", "--mu", "0.25"],
     {"y": 0.008, "load": 60000.0, "creepage": (0.001, -0.002, 0.1), "model": "hertz", "mu": 0.25}),
    (["--y", "-0.002", "--roll", "0.001", "--load", "78500", "--creepage", "0.002,0,0"],
     {"y": -0.002, "roll": 0.001, "load": 78500.0, "creepage": (0.002, 0.0, 0.0)}),
])
def test_same_as_railtab_eval_json(railtab_program, args, kwargs):
    assert railtab.evaluate(str(SCENE), **kwargs) == eval_json(railtab_program, *args)


def test_scene_object_and_vectorised_states():
    scene = railtab.Scene.load(SCENE)
    assert scene.name == "default_stripes"
    xi = np.array([0.0, 0.001, 0.002])
    many = railtab.evaluate(scene, y=0.003, load=78.5e3, creepage=np.c_[xi, 0 * xi, 0 * xi])
    assert len(many) == 3
    one = railtab.evaluate(scene, y=0.003, load=78.5e3, creepage=(0.002, 0.0, 0.0))
    assert many[2] == one
    fx = [sum(c["fx"] for c in r["wheels"][0]["contacts"]) for r in many]
    assert fx[0] == pytest.approx(0.0, abs=1.0) and fx[2] < fx[1] < 0.0   # braking creep force grows
    assert railtab.evaluate(scene, y=[0.0, 0.003], load=78.5e3)[1] == railtab.evaluate(scene, y=0.003, load=78.5e3)


def test_bad_input_is_refused_with_a_message(tmp_path):
    with pytest.raises(railtab.Error, match="missing.toml"):
        railtab.evaluate(tmp_path / "missing.toml", y=0.0)
    scene = railtab.Scene.load(SCENE)
    with pytest.raises(railtab.Error, match="load"):
        railtab.evaluate(scene, y=0.0, load=-1.0)
    with pytest.raises(railtab.Error, match="model"):
        railtab.evaluate(scene, y=0.0, model="magic")
    with pytest.raises(ValueError, match="creepage"):
        railtab.evaluate(scene, y=0.0, creepage=(0.0, 0.0))
    with pytest.raises(ValueError, match=r"y \(3,\), load \(2,\)"):   # named, not numpy's "arg 0", "arg 1"
        railtab.evaluate(scene, y=np.zeros(3), load=[7e4, 8e4])
    with pytest.raises(ValueError, match=r"y \(2,\), creepage \(3, 3\)"):
        railtab.evaluate(scene, y=[0.0, 0.001], creepage=np.zeros((3, 3)))
    with pytest.raises(railtab.Error, match=r"^y: must be a number in \[-0.1, 0.1\] m, got NaN"):  # not eval's --y
        railtab.evaluate(scene, y=np.nan)
    with pytest.raises(railtab.Error, match=r"^state 1 \(C order\): load: must be a number in \[0, 1e\+06\] N, got -1 N"):
        railtab.evaluate(scene, y=0.0, load=[7e4, -1.0])
