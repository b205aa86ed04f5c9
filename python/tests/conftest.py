# SPDX-License-Identifier: Apache-2.0
"""Shared fixtures of the Python tests. CTest (python/CMakeLists.txt) sets the environment:
PYTHONPATH (the built package), RAILTAB_PROGRAM (the railtab program), RAILTAB_WRITE_FIXTURE
(tests/lookup's fixture table writer), RAILTAB_SOURCE_DIR, RAILTAB_TEST_TMP, and
RAILTAB_STRIPES_TABLE (the STRIPES table, generated once by the CTest fixture table.stripes_table)."""
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("RAILTAB_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def _program(variable):
    path = os.environ.get(variable)
    if not path or not Path(path).exists():
        pytest.skip(f"{variable} not set: run the Python tests through CTest (bash scripts/test.sh)")
    return path


@pytest.fixture(scope="session")
def railtab_program():
    """Path of the railtab program."""
    return _program("RAILTAB_PROGRAM")


@pytest.fixture(scope="session")
def fixture_table(tmp_path_factory):
    """A small format-2.0 table written by tests/lookup's fixture writer (y 9 x xi 5 x eta 3 x phi 3,
    2 slots, all parts; values from table_fixture.hpp's scene_sized_spec)."""
    path = tmp_path_factory.mktemp("fixture") / "fixture.h5"
    subprocess.run([_program("RAILTAB_WRITE_FIXTURE"), str(path)], check=True)
    return path


@pytest.fixture(scope="session")
def stripes_table(tmp_path_factory, railtab_program):
    """The table of tables/default_stripes.toml (the default track with STRIPES A&B + FASTSIM), made
    by `railtab generate` in a few seconds: the tests that read it test the format and the API, not
    the model (the exact default, tables/default.toml, takes minutes). Under CTest made once for all
    test files (RAILTAB_STRIPES_TABLE, read only), else once per pytest run."""
    shared = os.environ.get("RAILTAB_STRIPES_TABLE")
    if shared:
        if not Path(shared).exists():
            pytest.fail(f"RAILTAB_STRIPES_TABLE={shared} does not exist: the CTest fixture table.stripes_table failed")
        return Path(shared)
    path = tmp_path_factory.mktemp("stripes") / "default_stripes.h5"
    subprocess.run([railtab_program, "generate", str(SOURCE_DIR / "tables" / "default_stripes.toml"), "-o", str(path),
                    "--threads", "2"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return path


def fixture_value(wheel, part, output, slot, y, xi=0.0, eta=0.0, phi=0.0):
    """Value of tests/lookup/table_fixture.hpp's scene_sized_spec (part, output index in part)."""
    import numpy as np

    sign = 1.0 if wheel == 0 else -1.0
    return (1.0 + part + 0.1 * output + slot) * (sign * np.asarray(y) * 100.0 + np.sin(30.0 * np.asarray(xi))
                                                 + 0.5 * np.asarray(eta) ** 2 + 0.1 * np.asarray(phi))
