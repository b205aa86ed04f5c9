# SPDX-License-Identifier: Apache-2.0
"""Arguments that are not state arrays: numbers checked by the command line's reader
(core/number_input.hpp, through _railtab._check_number) and file paths without a NUL."""
import math
import numbers
import os

from . import _railtab


def checked_number(name, value, lo, hi, whole=False, unit=""):
    """`value` as a float in [lo, hi] (whole: an integer value). A non-number is a TypeError; NaN,
    infinity, a fraction where whole, or a value out of range is railtab.Error (a ValueError)
    naming `name`, as the railtab program's options are."""
    if isinstance(value, (str, bytes)) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a number, got {type(value).__name__} {value!r}"[:200])
    try:
        v = float(value)
    except OverflowError:  # an int beyond the double range: beyond any range
        v = math.copysign(math.inf, value)
    return _railtab._check_number(name, v, lo, hi, whole, unit)


def checked_path(name, path):
    """os.fspath(path), refused when it holds a NUL: C and HDF5 would read it cut at the NUL. Not a
    file name (None, a number, an open file) is a TypeError naming the argument."""
    try:
        p = os.fspath(path)
    except TypeError:
        raise TypeError(f"{name} must be a file name (str, bytes or os.PathLike), got {type(path).__name__} "
                        f"{path!r}"[:200]) from None
    if ("\0" if isinstance(p, str) else b"\0") in p:
        raise ValueError(f"{name}: {p!r} contains a NUL character: not a file name"[:300])
    return p
