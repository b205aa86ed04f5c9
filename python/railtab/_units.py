# SPDX-License-Identifier: Apache-2.0
"""SI units of the table's axes and outputs (docs/table-format.md)."""

AXIS_UNITS = {"y": "m", "roll": "rad", "yaw": "rad", "load": "N", "xi": "1", "eta": "1", "phi": "rad/m"}

OUTPUT_UNITS = {
    "contact_angle": "rad",
    "rolling_radius": "m",
    "wheel_y": "m",
    "rail_y": "m",
    "separation": "m",
    "curvature_a": "1/m",
    "curvature_b": "1/m",
    "normal_force": "N",
    "approach": "m",
    "area": "m2",
    "max_pressure": "Pa",
    "a": "m",
    "b": "m",
    "fx": "N",
    "fy": "N",
    "mz": "N m",
    "slip_fraction": "1",
    "wear_rate": "m2/m",
}
