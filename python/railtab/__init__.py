# SPDX-License-Identifier: Apache-2.0
"""railtab: wheel-rail contact tables and models for railway vehicle dynamics, from Python.

    import railtab
    table = railtab.Table.load("default.h5")           # a table made by `railtab generate`
    r = table.query("left", y=0.003, load=78.5e3, xi=[0.0, 0.001, 0.002])
    r["fx"]                                            # [N], dims (state, slot)

All quantities are SI (m, N, Pa, rad, s); frames and signs as in docs/conventions.md.
"""
from ._evaluate import Scene, evaluate
from ._railtab import Error, kalker_coefficients
from ._profile import Profile, write_simpack
from ._status import STATUS_FLAGS, decode_status, has_flag, status_names
from ._table import QueryResult, Table
from ._units import AXIS_UNITS, OUTPUT_UNITS

__all__ = ["AXIS_UNITS", "Error", "OUTPUT_UNITS", "Profile", "QueryResult", "STATUS_FLAGS", "Scene",
           "Table", "decode_status", "evaluate", "has_flag", "kalker_coefficients", "status_names", "write_simpack"]
