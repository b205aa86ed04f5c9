# SPDX-License-Identifier: Apache-2.0
"""Text from an input file never runs a command through gnuplot: every chart command (chart-geometry,
chart-pressure, chart-stability, chart, conicity, simulate's wear charts) draws its chart for a scene whose
name and description hold backquotes, $(...), '@' macros, quotes, backslashes and a newline; no
command runs, the titles come back word for word, and -q leaves stderr empty (no gnuplot warning).
The scenes are the hostile inputs of tests/data/hostile/ (README there)."""
import json
import re
import shutil
import subprocess

import pytest

from conftest import SOURCE_DIR

HOSTILE = SOURCE_DIR / "tests" / "data" / "hostile"
# Each piece would run `touch pwned_*` if gnuplot (or a shell) interpreted it; the quotes, the
# backslash and the newline would end a gnuplot string early; "µ" checks that UTF-8 survives.
NAME_TEXT = "x`touch pwned_name` $(touch pwned_dollar) @m 'q\" \\ {a_b} \u00b5"
DESCRIPTION_TEXT = "d`touch pwned_description`\nsecond line @m"


def decoded_gnuplot_strings(script):
    """Every double-quoted string of a gnuplot script, with gnuplot's escapes (\\ooo, \\n, \\\\, \\") decoded."""
    out = []
    for body in re.findall(r'"((?:[^"\\]|\\.)*)"', script):
        text = re.sub(r"\\([0-7]{3})", lambda m: chr(int(m.group(1), 8)), body)
        out.append(text.encode("latin-1").decode("utf-8"))
    return out


def hostile_scene(tmp_path):
    text = (HOSTILE / "gnuplot_backquote.toml").read_text()
    # JSON string escapes are TOML basic-string escapes.
    keys = f"name = {json.dumps(NAME_TEXT, ensure_ascii=False)}\ndescription = {json.dumps(DESCRIPTION_TEXT)}"
    text = re.sub(r'name = ".*"', lambda _: keys, text, count=1)
    (tmp_path / "scene.toml").write_text(text)
    return tmp_path / "scene.toml"


def check_no_command_ran(tmp_path):
    ran = sorted(p.name for p in tmp_path.rglob("pwned*"))
    assert not ran, f"gnuplot ran a command from the scene: {ran}"


CHARTS = {
    "chart-geometry": (["--y-min", "-0.002", "--y-max", "0.002", "--y-step", "0.001"], ["geometry.gp"]),
    "chart-pressure": ([], ["pressure.gp"]),
    "conicity": (["--amplitudes", "0.002", "0.004"], ["conicity.gp"]),
    "chart-stability": (["--y-min", "-0.002", "--y-max", "0.002", "--y-step", "0.002"], ["stability_map.gp"]),
    # Four CONTACT reference states keep the speed-accuracy run short (~15 s).
    "chart": (["--quick", "--repeats", "1", "--reference", str(HOSTILE / "blockC_four_states.csv")],
              ["speed_accuracy.gp", "table_memory.gp"]),
}


@pytest.mark.parametrize("command", sorted(CHARTS))
def test_chart_titles_run_nothing(railtab_program, tmp_path, command):
    args, scripts = CHARTS[command]
    scene = hostile_scene(tmp_path)
    r = subprocess.run([railtab_program, command, "--scene", str(scene), "--out", "out", "-q", *args],
                       cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""   # -q: no diagnostics, gnuplot's warnings included
    check_no_command_ran(tmp_path)
    for name in scripts:
        script = (tmp_path / "out" / name).read_text()
        assert "`" not in script and "@" not in script
        strings = decoded_gnuplot_strings(script)
        assert any(NAME_TEXT in s for s in strings), strings
        if command not in ("chart", "conicity"):   # these charts name the scene only
            assert any(DESCRIPTION_TEXT in s for s in strings), strings
        assert (tmp_path / "out" / name.replace(".gp", ".png")).stat().st_size > 0


def test_simulation_name_runs_nothing(railtab_program, tmp_path):
    for name in ("sim_backquote_name.toml", "sim_contact.toml"):
        shutil.copy(HOSTILE / name, tmp_path / name)
    r = subprocess.run([railtab_program, "simulate", "sim_backquote_name.toml", "--out", "out", "--threads", "1",
                        "--duration", "0.5", "-q"], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    check_no_command_ran(tmp_path)
    scripts = list((tmp_path / "out").rglob("wear*.gp"))
    assert scripts
    for gp in scripts:
        script = gp.read_text()
        assert "`" not in script and "@" not in script
        assert any("wear`touch pwned_by_simulation_name`" in s for s in decoded_gnuplot_strings(script))
        assert gp.with_suffix(".png").stat().st_size > 0
