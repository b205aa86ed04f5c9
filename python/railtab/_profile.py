# SPDX-License-Identifier: Apache-2.0
"""railtab.Profile: wheel and rail profiles from files (docs/profiles.md), on numpy arrays."""
import numpy as np

from . import _railtab
from ._inputs import checked_number, checked_path

# Sampling steps of sample() and write_simpack() [m]: a micrometre up to a centimetre.
_STEP = (1e-6, 0.01)


class Profile:
    """A wheel or rail profile z(u) in railtab's profile frame (docs/conventions.md): u [m]
    towards the field side, z [m] up. Read from SIMPACK .prw/.prr or two-column mm files."""

    def __init__(self, native):
        self._p = native

    @classmethod
    def read(cls, path, kind, smoothing_length=0.0):
        """kind: 'wheel' or 'rail'. smoothing_length [m]: 0 interpolates the points, > 0 is
        CONTACT's filter length. Raises railtab.Error (a ValueError) naming the file and line."""
        return cls(_railtab.Profile.read(checked_path("path", path), kind,
                                         checked_number("smoothing_length", smoothing_length, 0.0, 1.0, unit="m")))

    @classmethod
    def s1002(cls):
        """The standard S1002 wheel (EN 13715), from its analytic definition."""
        return cls(_railtab.Profile.s1002())

    @classmethod
    def uic60(cls):
        """The UIC60 (60E1) rail head, uninclined, from its standard definition."""
        return cls(_railtab.Profile.uic60())

    name = property(lambda self: self._p.name)
    kind = property(lambda self: self._p.kind)
    u_min = property(lambda self: self._p.u_min, doc="[m]")
    u_max = property(lambda self: self._p.u_max, doc="[m]")

    def __call__(self, u):
        """z(u) [m] at any array of u [m]; u outside [u_min, u_max] raises railtab.Error."""
        return self.evaluate(u)[0]

    def evaluate(self, u):
        """(z [m], dz/du [1], d2z/du2 [1/m]) at any array of u [m]."""
        z, dz, d2z = self._p._eval(np.asarray(u, dtype=np.float64))
        if np.ndim(u) == 0:
            return float(z), float(dz), float(d2z)
        return z, dz, d2z

    def sample(self, step=0.0002):
        """(u, z) every `step` [m] over the whole range, the last point at u_max."""
        step = checked_number("step", step, *_STEP, unit="m")
        u = np.arange(self.u_min, self.u_max, step)
        u = np.append(u[u < self.u_max - 1e-3 * step], self.u_max)
        return u, self(u)

    def write_simpack(self, path, step=0.0002, comment=""):
        """Writes the profile sampled every `step` [m] as a SIMPACK file (.prw wheel, .prr rail)."""
        u, z = self.sample(step)  # checks step
        write_simpack(path, self.kind, u, z, comment or self.name)

    def __repr__(self):
        return (f"<railtab.Profile {self.name!r} {self.kind}, u {self.u_min * 1e3:.3f} .. "
                f"{self.u_max * 1e3:.3f} mm>")


def write_simpack(path, kind, u, z, comment=""):
    """Writes points u, z [m] (profile frame, ascending u) as a SIMPACK .prw (wheel) / .prr (rail)."""
    _railtab._write_simpack(checked_path("path", path), kind, np.asarray(u, dtype=np.float64).tolist(),
                            np.asarray(z, dtype=np.float64).tolist(), comment)
