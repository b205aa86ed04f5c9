# SPDX-License-Identifier: Apache-2.0
"""Numbers on the railtab command line (one reader, core/number_input.hpp): an empty value, NaN,
infinity, a value beyond the option's documented range and a fraction where a count is meant are
each a usage error (exit 2) naming the option; nothing is computed or written. And `railtab query`
answers any number of states (--y, a states file, stdin) in bounded memory."""
import json
import resource
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

SCENE = str(SOURCE_DIR / "tables" / "default_stripes.toml")
SIM = str(SOURCE_DIR / "tables" / "sim" / "r600.toml")


def run(program, *args, **kw):
    return subprocess.run([program, *args], capture_output=True, text=True, timeout=60, **kw)


# (arguments after the command, the option the message must name). TABLE is the STRIPES table.
BAD = [
    (["query", "TABLE", "--y", "", "--load", "78500"], "--y"),
    (["query", "TABLE", "--y", "0.001,,0.002", "--load", "78500"], "--y"),
    (["query", "TABLE", "--y", "nan", "--load", "78500"], "--y"),
    (["query", "TABLE", "--y", "5", "--load", "78500"], "--y"),
    (["query", "TABLE", "--y", "0.001", "--load", ""], "--load"),
    (["query", "TABLE", "--y", "0.001", "--load", "inf"], "--load"),
    (["query", "TABLE", "--y", "0.001", "--load", "1e300"], "--load"),
    (["query", "TABLE", "--y", "0.001", "--load", "78500", "--roll", "-nan"], "--roll"),
    (["query", "TABLE", "--y", "0.001", "--load", "78500", "--creepage", "", "", ""], "--creepage"),
    (["query", "TABLE", "--y", "0.001", "--load", "78500", "--creepage", ",,"], "--creepage"),
    (["query", "TABLE", "--y", "0.001", "--load", "78500", "--creepage", "0.001,,0"], "--creepage"),
    (["query", "TABLE", "--y", "0.001", "--load", "78500", "--creepage", "1e200,0,0"], "--creepage"),
    (["eval", "--scene", SCENE, "--y", ""], "--y"),
    (["eval", "--scene", SCENE, "--y", "7"], "--y"),
    (["eval", "--scene", SCENE, "--y", "0.001", "--load", ""], "--load"),
    (["eval", "--scene", SCENE, "--y", "0.001", "--mu", ""], "--mu"),
    (["eval", "--scene", SCENE, "--y", "0.001", "--mu", "1e300"], "--mu"),
    (["eval", "--scene", SCENE, "--y", "0.001", "--roll", "3"], "--roll"),
    (["eval", "--scene", SCENE, "--y", "0.001", "--creepage", "", "", ""], "--creepage"),
    (["generate", SCENE, "-o", "OUT", "--threads", "100000"], "--threads"),
    (["generate", SCENE, "-o", "OUT", "--threads", "1.5"], "--threads"),
    (["generate", SCENE, "-o", "OUT", "--threads", ""], "--threads"),
    (["generate", SCENE, "-o", "OUT", "--max-points", "1.5"], "--max-points"),
    (["generate", SCENE, "-o", "OUT", "--max-points", ""], "--max-points"),
    (["generate", SCENE, "-o", "OUT", "--max-bytes", "nan"], "--max-bytes"),
    (["simulate", SIM, "--out", "OUT", "--threads", "100000"], "--threads"),
    (["simulate", SIM, "--out", "OUT", "--duration", ""], "--duration"),
    (["simulate", SIM, "--out", "OUT", "--duration", "inf"], "--duration"),
    (["chart-geometry", "--scene", SCENE, "--out", "OUT", "--y-step", ""], "--y-step"),
    (["chart-geometry", "--scene", SCENE, "--out", "OUT", "--y-min", "nan"], "--y-min"),
    (["chart-stability", "--scene", SCENE, "--out", "OUT", "--y-step", "1e-300"], "--y-step"),
    (["chart-pressure", "--scene", SCENE, "--out", "OUT", "--load", ""], "--load"),
    (["chart-pressure", "--scene", SCENE, "--out", "OUT", "--y", "inf"], "--y"),
    (["chart-pressure", "--scene", SCENE, "--out", "OUT", "--reference-pmax", "-1"], "--reference-pmax"),
    (["chart", "--scene", SCENE, "--out", "OUT", "--repeats", "1.5"], "--repeats"),
    (["chart", "--scene", SCENE, "--out", "OUT", "--repeats", ""], "--repeats"),
    (["conicity", "--scene", SCENE, "--out", "OUT", "--amplitudes", "0.001,,0.002"], "--amplitudes"),
    (["conicity", "--scene", SCENE, "--out", "OUT", "--y-step", ""], "--y-step"),
    (["conicity", "--scene", SCENE, "--out", "OUT", "--y-max", "nan"], "--y-max"),
]


@pytest.mark.parametrize("args,option", BAD, ids=[f"{a[0]}{option}-{k}" for k, (a, option) in enumerate(BAD)])
def test_bad_number_is_a_usage_error_naming_the_option(railtab_program, stripes_table, tmp_path, args, option):
    out = tmp_path / "out"
    args = [str(stripes_table) if a == "TABLE" else str(out) if a == "OUT" else a for a in args]
    r = run(railtab_program, *args)
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert r.stdout == ""
    assert r.stderr.startswith(option + ":") or f"\n{option}:" in r.stderr, r.stderr
    assert "must be" in r.stderr and "179769" not in r.stderr, r.stderr   # the rule, not CLI11's 300 digits
    assert not out.exists()


def test_good_numbers_are_read_in_every_spelling(railtab_program, stripes_table):
    base = ["query", str(stripes_table), "--load", "78500", "--wheel", "left", "--json"]
    one = json.loads(run(railtab_program, *base, "--y", "0.001,-0.002", "--creepage", "0.001,0,0").stdout)
    two = json.loads(run(railtab_program, *base, "--y", "+1e-3", "-0.002", "--creepage", "1e-3", "0", "0").stdout)
    assert one == two and [q["state"]["y"] for q in one["queries"]] == [0.001, -0.002]


def test_threads_at_the_bound_is_accepted(railtab_program, tmp_path):
    scene = (SOURCE_DIR / "tables" / "default_stripes.toml").read_text().replace(
        "phi = [-0.3, 0.0, 0.3]", "phi = [0.0]").replace("eta = [-0.004, -0.001, 0.0, 0.001, 0.004]", "eta = [0.0]")
    (tmp_path / "s.toml").write_text(scene)
    r = run(railtab_program, "generate", str(tmp_path / "s.toml"), "-o", str(tmp_path / "s.h5"), "--threads", "1024",
            "-q")
    # Capped at the cores: oneTBB's "number of workers is currently limited" warning never comes.
    assert r.returncode == 0 and r.stderr == "", r.stderr
    r = run(railtab_program, "generate", str(tmp_path / "s.toml"), "-o", str(tmp_path / "t.h5"), "--threads", "1025")
    assert r.returncode == 2 and "--threads: must be a whole number in [0, 1024], got 1025" in r.stderr


# --- railtab query: states streamed -------------------------------------------------------------

def test_states_file_and_stdin_give_the_output_of_y(railtab_program, stripes_table, tmp_path):
    ys = ["0.003", "-0.0042", "0", "0.0071"]
    (tmp_path / "states.csv").write_text("# y only\ny\n" + "\n".join(ys) + "\n")
    for fmt in ([], ["--json"]):
        base = ["query", str(stripes_table), "--load", "78500", "--creepage", "0.001,0,0", *fmt]
        expected = run(railtab_program, *base, "--y", ",".join(ys))
        from_file = run(railtab_program, *base, "--states", str(tmp_path / "states.csv"))
        from_stdin = run(railtab_program, *base, "--states", "-", input="y\n" + "\n".join(ys))  # no final line end
        assert expected.returncode == 0 and expected.stdout
        assert from_file.stdout == expected.stdout and from_stdin.stdout == expected.stdout
    assert len(json.loads(expected.stdout)["queries"]) == 2 * len(ys)


def test_states_file_columns_set_the_state(railtab_program, stripes_table, tmp_path):
    (tmp_path / "s.csv").write_text("y, load ,xi\n0.003,60000,0.001\n-0.002, 90000 ,0\n")
    j = json.loads(run(railtab_program, "query", str(stripes_table), "--states", str(tmp_path / "s.csv"),
                       "--wheel", "left", "--json").stdout)
    assert [(q["state"]["y"], q["state"]["load"], q["state"]["xi"]) for q in j["queries"]] == \
        [(0.003, 60000.0, 0.001), (-0.002, 90000.0, 0.0)]


@pytest.mark.parametrize("text,message", [
    ("", "empty: expected a header"),
    ("load\n78500\n", "header: no column y"),
    ("y,speed\n0,1\n", "header: unknown column 'speed'"),
    ("y,y\n0,0\n", "column y named twice"),
    ("y\n0.001\n\n0.002,1\n", "s.csv:4: 2 values, the header names 1 columns"),
    ("y\n0.001\n\n", None),
    ("y\n", "no states"),
    ("y\n0.5\n", "s.csv:2: column y: must be a number in [-0.1, 0.1] m, got 0.5 m"),
    ("y\n\n0.001\nnan\n", "s.csv:4: column y: must be"),
    ("y\n0.001\x00junk\n", "s.csv:2: column y: must be"),
    ("y\n" + "1" * 5000 + "\n", "s.csv:2: line longer than 4096 characters"),
])
def test_states_file_errors_name_the_file_and_line(railtab_program, stripes_table, tmp_path, text, message):
    (tmp_path / "s.csv").write_text(text)
    r = run(railtab_program, "query", str(stripes_table), "--states", str(tmp_path / "s.csv"), "--load", "78500")
    if message is None:
        assert r.returncode == 0, r.stderr
    else:
        assert r.returncode == 1 and message in r.stderr, r.stderr


def test_query_needs_y_or_states_and_not_both(railtab_program, stripes_table, tmp_path):
    (tmp_path / "s.csv").write_text("y\n0\n")
    assert run(railtab_program, "query", str(stripes_table), "--load", "78500").returncode == 2
    r = run(railtab_program, "query", str(stripes_table), "--load", "78500", "--y", "0", "--states",
            str(tmp_path / "s.csv"))
    assert r.returncode == 2 and "excludes" in r.stderr


def peak_rss_kib(command, stdin_text):
    """Peak resident memory of `command` fed `stdin_text`, measured by a fresh Python parent."""
    probe = ("import resource, subprocess, sys\n"
             "subprocess.run(sys.argv[1:], stdin=sys.stdin, stdout=subprocess.DEVNULL, check=True)\n"
             "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    r = subprocess.run([sys.executable, "-c", probe, *command], input=stdin_text, capture_output=True, text=True,
                       timeout=300, check=True)
    return int(r.stdout)


def test_query_memory_does_not_grow_with_the_states(railtab_program, stripes_table):
    # Each state's answer was kept until the end (about 12 KB each, 2.4 GB for 200k states); now
    # each is printed and dropped. 20x the states may not cost 20 MB more (it cost 230 MB).
    command = [railtab_program, "query", str(stripes_table), "--load", "78500", "--states", "-", "--json"]
    states = lambda n: "y\n" + "\n".join(f"{-0.009 + 0.018 * k / n:.6f}" for k in range(n)) + "\n"
    small = peak_rss_kib(command, states(1000))
    large = peak_rss_kib(command, states(20000))
    assert large < small + 20 * 1024, (small, large)
