# SPDX-License-Identifier: Apache-2.0
"""railtab.Table: a contact table loaded with railtab's lookup, queried on numpy arrays."""
import numpy as np

from . import _railtab
from ._inputs import checked_number, checked_path
from ._shapes import broadcast_named
from ._status import cf_flag_attributes
from ._units import AXIS_UNITS, OUTPUT_UNITS

_STATE = ("y", "roll", "load", "xi", "eta", "phi", "yaw")  # the lookup's Variable order (yaw last)
_CREEPAGES = ("xi", "eta", "phi")  # default 0 (pure rolling) when tabulated and not given
_WHEELS = {"left": 0, "right": 1}
# track_forces=True: names and units of the per-slot and per-state arrays, in the binding's order.
_TRACK_SLOT = (("track_lateral_force", "N"), ("track_vertical_force", "N"), ("track_contact_angle", "rad"))
# creep_coefficients=True: (force, creepage) of the binding's 9 values, force-major, and units.
_COEFFICIENTS = tuple((f, c) for f in ("fx", "fy", "mz") for c in ("xi", "eta", "phi"))
_COEFFICIENT_UNITS = {"fx": {"xi": "N", "eta": "N", "phi": "N m"}, "fy": {"xi": "N", "eta": "N", "phi": "N m"},
                      "mz": {"xi": "N m", "eta": "N m", "phi": "N m2"}}
_TRACK_WHEEL = (("wheel_lateral_force", "N"), ("wheel_vertical_force", "N"), ("y_force", "N"), ("q_force", "N"),
                ("y_over_q", "1"))


def _wheel_codes(wheel):
    """'left'/'right'/0/1, or an array of them, as int32 codes 0/1. A number other than exactly 0
    or 1 (0.7, 2**32, -1, NaN) is refused, never cut to an int32."""
    if isinstance(wheel, str):
        if wheel not in _WHEELS:
            raise ValueError(f"wheel must be 'left' or 'right', got {wheel!r}")
        return np.array(_WHEELS[wheel], dtype=np.int32)
    arr = np.asarray(wheel)
    if arr.dtype.kind in "US":
        bad = set(np.unique(arr)) - set(_WHEELS)
        if bad:
            raise ValueError(f"wheel must be 'left' or 'right', got {sorted(bad)}")
        return (arr == "right").astype(np.int32)
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"wheel must be 'left', 'right', 0 or 1, got an array of {arr.dtype}")
    bad = ~np.isin(arr, (0, 1))
    if bad.any():  # the first offender, in the words of the number reader
        checked_number("wheel (0 = left, 1 = right)", arr[bad].flat[0].item(), 0, 1, whole=True)
    return arr.astype(np.int32)


def _flat(arr, shape, n):
    """One value, or the array broadcast to `shape` and flattened (a view when possible)."""
    if arr.size == 1:
        return arr.reshape(1)
    return np.broadcast_to(arr, shape).reshape(n)


class QueryResult(dict):
    """Named arrays of a query (used when xarray is absent, or with as_xarray=False).

    Keys: every output of the table's parts, 'status' and 'part_status', and the state variables
    given. `units[name]` gives the SI unit, `dims[name]` the dimension names, `attrs` the table."""

    def __init__(self):
        super().__init__()
        self.units = {}
        self.dims = {}
        self.attrs = {}


class Table:
    """A wheel-rail contact table (docs/table-format.md), loaded once, queried vectorised."""

    def __init__(self, path, method="linear"):
        """Loads a table file, as Table.load(path, method) does."""
        if not isinstance(method, str):
            raise TypeError(f"method must be 'linear', 'cubic' or 'monotone-cubic', got {type(method).__name__} "
                            f"{method!r}"[:200])
        self._t = _railtab.Table.load(checked_path("path", path), method)

    @classmethod
    def load(cls, path, method="linear"):
        """Loads a table file. method: 'linear' (default), 'cubic' or 'monotone-cubic'.

        Raises OSError naming the file and the problem (missing, not a regular file, corrupt,
        unknown version), TypeError when path is not a file name."""
        return cls(path, method)

    path = property(lambda self: self._t.path)
    method = property(lambda self: self._t.method)
    n_slots = property(lambda self: self._t.n_slots)
    parts = property(lambda self: self._t.parts, doc="parts held: 'geometry', 'normal', ...")
    axes = property(lambda self: self._t.axes, doc="tabulated axes: name -> nodes (SI)")
    fixed_axes = property(lambda self: self._t.fixed_axes, doc="untabulated variables -> value")
    format_version = property(lambda self: self._t.format_version)
    scene_name = property(lambda self: self._t.scene_name)
    memory_bytes = property(lambda self: self._t.memory_bytes)
    has_creep_coefficients = property(lambda self: self._t.has_creep_coefficients)  # format 2.3 tables
    has_error_map = property(lambda self: self._t.has_error_map, doc="the table carries an error map (2.3)")
    yaw_even = property(lambda self: self._t.yaw_even,
                        doc="the yaw axis is the non-negative half of a symmetric one: a query reads |yaw| (2.4)")

    def error_estimate(self, y, slot):
        """The table's stored error map where a query at lateral displacement y [m] lands in `slot`
        (0 tread, 1 flange): {"y_band": (start, end) [m], "table_vs_model": {...},
        "model_vs_exact": {...} | "same model" | None}, each comparison with "samples" and
        "<q>_rms" / "<q>_max" for q in fx, fy (% of mu N), mz (% of mu N c), normal_force (%),
        contact_angle (rad); NaN where the region has no sample. None when the table has no map
        (format before 2.3) or y is outside it."""
        if slot not in range(self.n_slots):
            raise ValueError(f"slot must be 0 .. {self.n_slots - 1}, got {slot!r}")
        return self._t.error_estimate(float(y), int(slot))

    def outputs(self):
        """Names of the outputs this table holds, in file order."""
        parts = set(self.parts)
        return [name for name, part in _railtab.OUTPUTS if part in parts]

    def __repr__(self):
        axes = ", ".join(f"{k}[{len(v)}]" for k, v in self.axes.items())
        return f"<railtab.Table {self.path!r} scene={self.scene_name!r} axes: {axes}>"

    def query(self, wheel, y=None, roll=None, load=None, xi=None, eta=None, phi=None, yaw=None, *, slot=None,
              derivatives=False, track_forces=False, creep_coefficients=False, as_xarray=None):
        """Interpolates the table at many states at once.

        wheel: 'left', 'right' (or 0, 1, or an array of them). y [m], roll [rad], load [N],
        xi, eta [1], phi [rad/m], yaw [rad]: numbers or numpy arrays, broadcast against each other
        (numpy rules). A tabulated y, roll, yaw or load must be given; a creepage axis not given is 0; an
        untabulated variable defaults to the table's fixed value (another value is flagged
        out_of_range, as in the C++ lookup; a table without yaw holds yaw 0 only). slot: None for every slot (0 = tread, 1 = flange),
        or one slot only (half the cost).

        Returns an xarray.Dataset when xarray is installed (as_xarray=None) or asked for
        (as_xarray=True), else a QueryResult dict. Either way every output of the table's parts
        has dims (*state dims, 'slot') and SI units; 'status' holds the status bits with the CF
        attributes flag_masks / flag_meanings (railtab.decode_status turns them into text);
        'part_status' holds them per part. Never extrapolates: outside the table the values are
        clamped to the edge and flagged out_of_range. A NaN or infinite state does not raise (one
        bad state must not lose a batch): its outputs are 0 and flagged invalid_input.

        derivatives=True adds, for every output and every tabulated axis, the exact partial
        derivative of the interpolant 'd_<output>_d_<axis>' (e.g. d_fx_d_xi [N], d_fy_d_y [N/m]),
        same dims as the output, units output unit per axis unit; 0 where the axis was clamped to
        the table's range. Methods 'linear' and 'cubic' (ValueError for 'monotone-cubic').

        track_forces=True (every slot: not with slot=...) adds the forces of the rail on the wheel in
        track axes (docs/conventions.md, "Track-frame forces and Y/Q"; the C++ lookup's track_forces):
        per slot 'track_lateral_force' (along track y, + left) and 'track_vertical_force' (along track
        z, + up) [N] and 'track_contact_angle' [rad], the angle each slot was rotated with; per state
        'wheel_lateral_force', 'wheel_vertical_force' [N] (sums over the slots), 'y_force' (Y, the
        wheel's lateral force on its rail, + towards that rail's field side), 'q_force' (Q, its
        vertical force on the rail, + down) [N] and 'y_over_q' [1] (0 where Q <= 0).

        creep_coefficients=True adds each slot's linear creep coefficients (tables of format 2.3;
        docs/conventions.md, "Linear creep coefficients"): 'creep_coefficient_<f>_<c>' = d f / d c at
        zero creepage in full adhesion for f in fx, fy, mz and c in xi, eta, phi (e.g.
        creep_coefficient_fx_xi [N], -G c^2 C11 on an ellipse), interpolated over y, roll and load
        (the creepages given do not change them), one-sided at contact jumps. ValueError for a table
        without them (format 2.2 and older: Table.has_creep_coefficients is False).

        Raises TypeError for a missing tabulated variable or a complex value, ValueError for
        shapes that do not broadcast (naming each argument's shape), an unknown wheel or slot.
        """
        given = {"y": y, "roll": roll, "load": load, "xi": xi, "eta": eta, "phi": phi, "yaw": yaw}
        fixed = self.fixed_axes
        axes = self.axes
        values = {}
        for name in _STATE:
            v = given[name]
            if v is None:
                if name in fixed:
                    v = fixed[name]
                elif name in axes and name not in _CREEPAGES:
                    raise TypeError(f"{name} is an axis of {self.path}: give {name}=... "
                                    f"(range {axes[name][0]:g} .. {axes[name][-1]:g} {AXIS_UNITS[name]})")
                else:
                    v = 0.0
            arr = np.asarray(v)
            if arr.dtype.kind == "c":  # numpy would only warn and drop the imaginary part
                raise TypeError(f"{name} must be real, got a complex array")
            values[name] = np.asarray(arr, dtype=np.float64)
        codes = _wheel_codes(wheel)
        shape = broadcast_named("the state arrays",
                                {"wheel": codes.shape, **{k: values[k].shape for k in _STATE if given[k] is not None}})
        n = int(np.prod(shape, dtype=np.int64))
        slot_arg = -1 if slot is None else int(checked_number("slot", slot, 0, self.n_slots - 1, whole=True))
        raw, part_status, status, deriv, track, coefficients = self._t._query_arrays(
            n, _flat(codes, shape, n), *(_flat(values[k], shape, n) for k in _STATE), slot_arg,
            bool(derivatives), bool(track_forces), bool(creep_coefficients))
        slots = raw.shape[1]
        raw = raw.reshape(shape + (slots, raw.shape[2]))
        part_status = part_status.reshape(shape + (slots, part_status.shape[2]))
        status = status.reshape(shape + (slots,))
        state_dims = ("state",) if len(shape) == 1 else tuple(f"state_{i}" for i in range(len(shape)))
        slot_coord = np.arange(slots) if slot is None else np.array([slot_arg])
        out = QueryResult()
        out.attrs = {"table": self.path, "scene_name": self.scene_name, "method": self.method,
                     "format_version": self.format_version}
        parts = set(self.parts)
        for k, (name, part) in enumerate(_railtab.OUTPUTS):
            if part in parts:
                out[name] = raw[..., k]
                out.units[name] = OUTPUT_UNITS[name]
                out.dims[name] = state_dims + ("slot",)
        if deriv is not None:
            deriv = deriv.reshape(shape + (slots,) + deriv.shape[2:])
            for k, (name, part) in enumerate(_railtab.OUTPUTS):
                if part not in parts:
                    continue
                for v, axis in enumerate(_STATE):
                    if axis in axes:
                        key = f"d_{name}_d_{axis}"
                        out[key] = deriv[..., k, v]
                        out.units[key] = _per(OUTPUT_UNITS[name], AXIS_UNITS[axis])
                        out.dims[key] = state_dims + ("slot",)
        if coefficients is not None:
            coefficients = coefficients.reshape(shape + (slots, 9))
            for k, (f, c) in enumerate(_COEFFICIENTS):
                key = f"creep_coefficient_{f}_{c}"
                out[key] = coefficients[..., k]
                out.units[key] = _COEFFICIENT_UNITS[f][c]
                out.dims[key] = state_dims + ("slot",)
        if track is not None:
            per_slot, per_wheel = track
            per_slot = per_slot.reshape(shape + (slots, 3))
            per_wheel = per_wheel.reshape(shape + (5,))
            for k, (name, unit) in enumerate(_TRACK_SLOT):
                out[name] = per_slot[..., k]
                out.units[name] = unit
                out.dims[name] = state_dims + ("slot",)
            for k, (name, unit) in enumerate(_TRACK_WHEEL):
                out[name] = per_wheel[..., k]
                out.units[name] = unit
                out.dims[name] = state_dims
        out["status"] = status
        out.dims["status"] = state_dims + ("slot",)
        out["part_status"] = part_status
        out.dims["part_status"] = state_dims + ("slot", "part")
        out["slot"] = slot_coord
        out.dims["slot"] = ("slot",)
        for name in _STATE:
            if given[name] is not None:
                out[name] = np.broadcast_to(values[name], shape)
                out.units[name] = AXIS_UNITS[name]
                out.dims[name] = state_dims
        out["wheel"] = np.broadcast_to(codes, shape)
        out.dims["wheel"] = state_dims
        if as_xarray is None:
            try:
                import xarray  # noqa: F401
                as_xarray = True
            except ImportError:
                as_xarray = False
        return _to_xarray(out, given) if as_xarray else out


def _per(unit, axis_unit):
    """Units of d output / d axis: 'N' per 'm' is 'N/m', per '1' stays 'N', per 'rad/m' is 'N/(rad/m)'."""
    if axis_unit == "1":
        return unit
    axis = f"({axis_unit})" if "/" in axis_unit or " " in axis_unit else axis_unit
    return f"{unit}/{axis}"


def _to_xarray(result, given):
    """The QueryResult as an xarray.Dataset: state variables and slot as coordinates."""
    import xarray as xr

    coords = {"slot": ("slot", result["slot"], {"description": "0 = tread, 1 = flange"}),
              "part": ("part", np.array(_railtab.PARTS)),
              "wheel": (result.dims["wheel"], result["wheel"], {"description": "0 = left, 1 = right"})}
    for name in _STATE:
        if given[name] is not None:
            coords[name] = (result.dims[name], result[name], {"units": result.units[name]})
    data = {}
    for name, arr in result.items():
        if name in coords:
            continue
        attrs = {"units": result.units[name]} if name in result.units else {}
        if name in ("status", "part_status"):
            attrs.update(cf_flag_attributes())
        data[name] = (result.dims[name], arr, attrs)
    return xr.Dataset(data, coords=coords, attrs=result.attrs)
