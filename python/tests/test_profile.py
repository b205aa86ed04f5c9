# SPDX-License-Identifier: Apache-2.0
"""railtab.Profile: built-in and file profiles on numpy arrays; the SIMPACK writer round trip."""
import numpy as np
import pytest

import railtab
from conftest import SOURCE_DIR

SHARED = SOURCE_DIR.parent / "shared" / "profiles"


def test_builtin_s1002_and_uic60():
    wheel = railtab.Profile.s1002()
    assert wheel.kind == "wheel" and wheel.u_min < -0.06 and wheel.u_max == pytest.approx(0.060)
    z, dz, d2z = wheel.evaluate(np.array([0.0, 0.01]))
    assert z[0] == pytest.approx(0.0, abs=1e-12)   # running circle at the origin
    assert wheel(-0.055) == pytest.approx(-0.028, abs=1e-6)   # flange height 28 mm at u = -55 mm (docs)
    assert isinstance(wheel(0.0), float)
    rail = railtab.Profile.uic60()
    assert rail.kind == "rail" and rail(0.0) == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(railtab.Error):
        wheel(1.0)   # outside the profile


def test_two_column_file_and_errors(tmp_path):
    f = tmp_path / "parabola.txt"
    f.write_text("".join(f"{y} {0.01 * y * y}\n" for y in range(-30, 31)))  # mm, z down, a 60 mm crown
    p = railtab.Profile.read(f, "rail")
    assert p.name == "parabola" and p.u_min == pytest.approx(-0.030)
    assert p(0.003) == pytest.approx(-0.01 * 3 * 3 * 1e-3, rel=1e-9)          # z up, metres
    bad = tmp_path / "bad.txt"
    bad.write_text("1 2\n3 x\n")
    with pytest.raises(railtab.Error, match=r"bad.txt:2"):
        railtab.Profile.read(bad, "rail")
    with pytest.raises(ValueError, match="kind"):
        railtab.Profile.read(f, "axle")


def test_simpack_round_trip(tmp_path):
    wheel = railtab.Profile.s1002()
    path = tmp_path / "s1002.prw"
    wheel.write_simpack(path, step=0.0005)
    text = path.read_text()
    assert "type           =  1" in text and "point.begin" in text
    back = railtab.Profile.read(path, "wheel")
    u, z = wheel.sample(0.0005)
    np.testing.assert_allclose(back(u), z, atol=1e-15)
    assert back.u_max == pytest.approx(wheel.u_max, abs=1e-15)
    with pytest.raises(railtab.Error, match=".prr"):
        railtab.write_simpack(tmp_path / "rail.prw", "rail", u, z)


def test_write_simpack_goes_through_the_safe_output_path(tmp_path):
    """A FIFO, a symbolic link or a second name of another file at the target is refused; a link
    planted at PATH.tmp is not followed (the temporary is created exclusively)."""
    import os
    wheel = railtab.Profile.s1002()
    (tmp_path / "victim.txt").write_text("precious")
    os.mkfifo(tmp_path / "f.prw")
    os.symlink("victim.txt", tmp_path / "soft.prw")
    os.link(tmp_path / "victim.txt", tmp_path / "hard.prw")
    for name, problem in (("f.prw", "FIFO"), ("soft.prw", "symbolic link"), ("hard.prw", "hard links")):
        with pytest.raises(railtab.Error, match=problem):
            wheel.write_simpack(tmp_path / name)
    os.symlink("victim.txt", tmp_path / "z.prw.tmp")
    wheel.write_simpack(tmp_path / "z.prw")
    assert (tmp_path / "victim.txt").read_text() == "precious"
    assert (tmp_path / "f.prw").is_fifo() and (tmp_path / "z.prw").read_text().startswith("! SIMPACK")


@pytest.mark.skipif(not SHARED.exists(), reason=f"{SHARED} absent (reference data, optional)")
def test_manchester_benchmark_wheel_is_s1002():
    mbench = railtab.Profile.read(SHARED / "MBench_S1002_v3.prw", "wheel")
    u = np.linspace(-0.06, 0.055, 200)
    # 1.6e-6 mm at the file's points (docs/profiles.md); between them the spline through the
    # points departs from the analytic curve by up to 0.38 um (near the flange-root joints).
    np.testing.assert_allclose(mbench(u), railtab.Profile.s1002()(u), atol=5e-7)
