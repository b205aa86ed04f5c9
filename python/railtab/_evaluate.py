# SPDX-License-Identifier: Apache-2.0
"""railtab.evaluate: the direct contact models at one wheelset state (the code of `railtab eval`)."""
import json
import re

import numpy as np

from . import _railtab
from ._inputs import checked_path
from ._shapes import broadcast_named


class Scene:
    """A scene file (docs/scenes.md) loaded once: profiles, track, models. evaluate() takes one of
    these or a path (then the scene is loaded on every call)."""

    def __init__(self, path):
        """Loads a scene file, as Scene.load(path) does."""
        self._s = _railtab.Scene.load(checked_path("path", path))

    @classmethod
    def load(cls, path):
        """Raises railtab.Error (a ValueError) naming the file and the problem, TypeError when
        path is not a file name."""
        return cls(path)

    name = property(lambda self: self._s.name)
    path = property(lambda self: self._s.path)

    def __repr__(self):
        return f"<railtab.Scene {self.name!r} from {str(self.path)!r}>"


def _python_names(message):
    """The shared evaluation code (railtab eval) names its command-line options; say the keywords."""
    message = message.replace("--equilibrium-roll", "equilibrium_roll")
    return re.sub(r"--(y|roll|yaw|load|creepage|mu|model)\b", r"\1", message)


def _one(scene, y, roll, equilibrium_roll, load, model, creepage, mu, yaw, state=None):
    try:
        return _evaluate(scene, y, roll, equilibrium_roll, load, model, creepage, mu, yaw)
    except _railtab.Error as e:
        where = "" if state is None else f"state {state} (C order): "
        raise _railtab.Error(where + _python_names(str(e))) from None


def _evaluate(scene, y, roll, equilibrium_roll, load, model, creepage, mu, yaw):
    text = _railtab._evaluate_json(scene._s, float(y), None if roll is None else float(roll), bool(equilibrium_roll),
                                   None if load is None else float(load), model or "",
                                   [] if creepage is None else [float(c) for c in creepage],
                                   None if mu is None else float(mu), None if yaw is None else float(yaw))
    return json.loads(text)


def evaluate(scene, y, *, roll=None, load=None, creepage=None, model=None, mu=None, equilibrium_roll=False,
             yaw=None):
    """The direct models at a wheelset state: the same dict as `railtab eval --json` (SI units).

    scene: a Scene or a scene file path. y [m] lateral displacement; roll [rad] (default: the
    scene's choice, e.g. its equilibrium roll); yaw [rad] (angle of attack, default: the scene's
    first yaw, 0 without one); load [N] vertical wheel load (default: the
    scene's first); creepage (xi, eta, phi) [1, 1, rad/m] adds creep forces and wear (default:
    none); model: normal model name overriding the scene's ('hertz', 'stripes-ab', ...); mu:
    friction overriding the scene's.

    y and load may be arrays and creepage an (n, 3) array: then the states are broadcast and a
    list of dicts is returned, one per state in C order. Keys per wheel: 'contacts' (loaded
    patches: normal_force, approach, area, max_pressure, fx, fy, mz, slip_fraction, wear_rate,
    status ...) and 'rigid_points' (the geometry)."""
    if not isinstance(scene, Scene):
        scene = Scene.load(scene)
    y_arr = np.asarray(y, dtype=np.float64)
    load_arr = None if load is None else np.asarray(load, dtype=np.float64)
    c_arr = None if creepage is None else np.asarray(creepage, dtype=np.float64)
    if c_arr is not None and c_arr.shape[-1:] != (3,):
        raise ValueError(f"creepage must be (xi, eta, phi) or an (n, 3) array, got shape {c_arr.shape}")
    vectorised = y_arr.ndim > 0 or (load_arr is not None and load_arr.ndim > 0) or (c_arr is not None and c_arr.ndim > 1)
    if not vectorised:
        return _one(scene, y_arr, roll, equilibrium_roll, load_arr, model, c_arr, mu, yaw)
    shapes = {"y": y_arr.shape, **({"load": load_arr.shape} if load_arr is not None else {}),
              **({"creepage": c_arr.shape[:-1]} if c_arr is not None else {})}
    shape = broadcast_named("y, load and creepage (without its last axis of 3)", shapes,
                            {**shapes, **({"creepage": c_arr.shape} if c_arr is not None else {})})
    ys = np.broadcast_to(y_arr, shape).ravel()
    loads = None if load_arr is None else np.broadcast_to(load_arr, shape).ravel()
    cs = None if c_arr is None else np.broadcast_to(c_arr, shape + (3,)).reshape(-1, 3)
    return [_one(scene, ys[k], roll, equilibrium_roll, None if loads is None else loads[k], model,
                 None if cs is None else cs[k], mu, yaw, state=k) for k in range(ys.size)]
