# SPDX-License-Identifier: Apache-2.0
"""railtab writes only where it was asked, through its one output path: --resume refuses a
symbolic link, a hard link or a FIFO planted as OUTPUT.partial (the file it leads to is untouched),
-o refuses a profile of the scene, merge refuses a shard that is not a regular file at once
instead of waiting on it. Inputs: tests/data/hostile/ (README there)."""
import os
import shutil
import subprocess

import pytest

from conftest import SOURCE_DIR

HOSTILE = SOURCE_DIR / "tests" / "data" / "hostile"
PROFILES = SOURCE_DIR / "tests" / "data" / "profiles"


def run(program, *args, cwd):
    return subprocess.run([program, *args], cwd=cwd, capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("plant, problem", [("symlink", "symbolic link"), ("hardlink", "hard links"),
                                            ("fifo", "FIFO")])
def test_resume_refuses_a_planted_partial_file(railtab_program, tmp_path, plant, problem):
    shutil.copy(HOSTILE / "small.toml", tmp_path)
    (tmp_path / "victim.txt").write_text("precious data\n")
    partial = tmp_path / "out.h5.partial"
    {"symlink": lambda: os.symlink("victim.txt", partial), "hardlink": lambda: os.link(tmp_path / "victim.txt", partial),
     "fifo": lambda: os.mkfifo(partial)}[plant]()
    r = run(railtab_program, "generate", "small.toml", "-o", "out.h5", "--threads", "1", "--resume", "-q", cwd=tmp_path)
    assert r.returncode == 1 and "out.h5.partial" in r.stderr and problem in r.stderr, r.stderr
    assert (tmp_path / "victim.txt").read_text() == "precious data\n"
    assert not (tmp_path / "out.h5").exists()


def test_output_may_not_replace_a_profile_of_the_scene(railtab_program, tmp_path):
    for name in ("Car7216_0001r.whl", "avg_HR.BAN"):
        shutil.copy(PROFILES / name, tmp_path)
    (tmp_path / "worn.toml").write_text(
        '[scene]\nname = "worn"\n[profiles]\nwheel = "Car7216_0001r.whl"\nrail = "avg_HR.BAN"\n[contact]\n'
        'normal_model = "hertz"\n[grid]\ny = { start = -0.004, stop = 0.004, count = 3 }\nload = 80e3\n')
    before = (tmp_path / "avg_HR.BAN").read_bytes()
    for target in ("avg_HR.BAN", "./avg_HR.BAN", "Car7216_0001r.whl"):
        r = run(railtab_program, "generate", "worn.toml", "-o", target, "--threads", "1", "-q", cwd=tmp_path)
        assert r.returncode == 1 and "is the input" in r.stderr, (target, r.stderr)
    assert (tmp_path / "avg_HR.BAN").read_bytes() == before


def test_merge_refuses_a_fifo_shard_at_once(railtab_program, tmp_path):
    shutil.copy(HOSTILE / "small.toml", tmp_path)
    r = run(railtab_program, "generate", "small.toml", "-o", "s1.h5", "--shard", "1/2", "--threads", "1", "-q",
            cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    os.mkfifo(tmp_path / "s2.h5")
    r = subprocess.run([railtab_program, "merge", "m.h5", "s1.h5", "s2.h5"], cwd=tmp_path, capture_output=True,
                       text=True, timeout=30)  # it used to wait forever for a writer
    assert r.returncode == 1 and "s2.h5" in r.stderr and "FIFO" in r.stderr, r.stderr
    assert not (tmp_path / "m.h5").exists()
