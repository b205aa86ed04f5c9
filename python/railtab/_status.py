# SPDX-License-Identifier: Apache-2.0
"""Status bits of every table point and query (docs/table-format.md, src/core/status.hpp)."""
import numpy as np

# (name, mask) in bit order; the same names as src/core/status.hpp's status::describe and the
# CF attributes flag_meanings / flag_masks of every status dataset.
STATUS_FLAGS = (
    ("converged", 1 << 0),
    ("not_converged", 1 << 1),
    ("two_point", 1 << 2),
    ("lift_off", 1 << 3),
    ("curvature_clipped", 1 << 4),
    ("curvature_shifted", 1 << 5),
    ("fallback_model", 1 << 6),
    ("flange_contact", 1 << 7),
    ("non_hertzian", 1 << 8),
    ("full_slip", 1 << 9),
    ("out_of_range", 1 << 10),
    ("invalid_input", 1 << 11),
    ("profile_edge", 1 << 12),
    ("failed", 1 << 13),
    ("area_too_small", 1 << 14),
    ("not_planar", 1 << 15),
    ("near_equal_minima", 1 << 16),
    ("curvature_step", 1 << 17),
    ("low_confidence", 1 << 18),
)
_MASK = dict(STATUS_FLAGS)


def status_names(bits):
    """Names of the set bits of one status value, e.g. ['converged', 'two_point']."""
    bits = int(bits)
    return [name for name, mask in STATUS_FLAGS if bits & mask]


def decode_status(bits):
    """Status as text: 'converged,two_point' ('none' for 0), the form of `railtab eval`.

    A scalar gives a str; an array gives an array of str of the same shape (each distinct value
    decoded once, so a million states cost one numpy pass)."""
    arr = np.asarray(bits)
    if arr.ndim == 0:
        return ",".join(status_names(arr)) or "none"
    values, inverse = np.unique(arr.astype(np.uint32), return_inverse=True)
    text = np.array([",".join(status_names(v)) or "none" for v in values], dtype=object)
    return text[inverse].reshape(arr.shape)


def has_flag(bits, name):
    """Boolean array: where the flag `name` (e.g. 'out_of_range') is set."""
    if name not in _MASK:
        raise ValueError(f"unknown status flag {name!r}; known: {', '.join(_MASK)}")
    return (np.asarray(bits).astype(np.uint32) & np.uint32(_MASK[name])) != 0


def cf_flag_attributes():
    """CF-convention attributes of a status variable (flag_masks, flag_meanings)."""
    return {
        "flag_masks": np.array([m for _, m in STATUS_FLAGS], dtype=np.uint32),
        "flag_meanings": " ".join(n for n, _ in STATUS_FLAGS),
    }
