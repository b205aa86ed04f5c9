# SPDX-License-Identifier: Apache-2.0
"""Broadcasting of named argument arrays, with errors that name them (numpy counts positions)."""
import numpy as np


def broadcast_named(what, shapes, shown=None):
    """The broadcast shape of `shapes` ({name: shape}); a ValueError naming each one with its shape
    in `shown` (default: `shapes`; e.g. the whole array where only its leading axes broadcast)."""
    try:
        return np.broadcast_shapes(*shapes.values())
    except ValueError:  # numpy's message counts arguments of this call, not the user's names
        raise ValueError(f"{what} do not broadcast against each other (numpy rules): "
                         + ", ".join(f"{k} {s}" for k, s in (shown or shapes).items())) from None
