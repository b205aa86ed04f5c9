# SPDX-License-Identifier: Apache-2.0
"""The railtab program's hygiene (docs/reliability.md, "`railtab query` streams"): results on
stdout, diagnostics on stderr,
-q/--quiet on every command, exit codes documented in --help, an unwritable output refused
before any work starts."""
import subprocess

import pytest

from conftest import SOURCE_DIR

COMMANDS = ["eval", "generate", "inspect", "query", "merge", "chart-geometry", "chart-pressure", "chart-stability",
            "chart", "simulate", "conicity", "export"]
SCENE = str(SOURCE_DIR / "tables" / "default_stripes.toml")


def run(program, *args, **kw):
    return subprocess.run([program, *args], capture_output=True, text=True, **kw)


def test_help_documents_exit_codes(railtab_program):
    r = run(railtab_program, "--help")
    assert r.returncode == 0
    for code in ("0 success", "1 error", "2 usage error", "130 interrupted"):
        assert code in r.stdout


@pytest.mark.parametrize("command", COMMANDS)
def test_every_command_has_quiet(railtab_program, command):
    r = run(railtab_program, command, "--help")
    assert r.returncode == 0 and "-q,--quiet" in r.stdout


def test_usage_error_is_exit_code_2(railtab_program):
    r = run(railtab_program, "eval", "--no-such-option")
    assert r.returncode == 2 and r.stdout == "" and "no-such-option" in r.stderr


def test_results_on_stdout_diagnostics_on_stderr(railtab_program, stripes_table, tmp_path):
    for args in (["eval", "--scene", SCENE, "--y", "0.002", "--json"],
                 ["query", str(stripes_table), "--y", "0.002", "--load", "78500"],
                 ["inspect", str(stripes_table)]):
        r = run(railtab_program, *args)
        assert r.returncode == 0 and r.stdout and r.stderr == "", args
    scene = (SOURCE_DIR / "tables" / "default_stripes.toml").read_text().replace(
        "phi = [-0.3, 0.0, 0.3]", "phi = [0.0]").replace("eta = [-0.004, -0.001, 0.0, 0.001, 0.004]", "eta = [0.0]")
    (tmp_path / "s.toml").write_text(scene)
    r = run(railtab_program, "generate", str(tmp_path / "s.toml"), "-o", str(tmp_path / "s.h5"), "--threads", "1")
    assert r.returncode == 0 and r.stdout == "" and r.stderr      # progress and summary on stderr
    r = run(railtab_program, "generate", str(tmp_path / "s.toml"), "-o", str(tmp_path / "q.h5"), "-q")
    assert r.returncode == 0 and r.stdout == "" and r.stderr == ""
    assert (tmp_path / "q.h5").exists()


@pytest.mark.parametrize("args", [
    ["generate", SCENE, "-o", "/proc/railtab-not-writable/t.h5"],
    ["generate", SCENE, "-o", "/nonexistent-railtab-dir/t.h5"],
    ["simulate", str(SOURCE_DIR / "tables" / "sim" / "r600.toml"), "--out", "/proc/railtab-not-writable"],
    ["chart-stability", "--scene", SCENE, "--out", "/proc/railtab-not-writable"],
    ["conicity", "--scene", SCENE, "--out", "/proc/railtab-not-writable"],
])
def test_unwritable_output_refused_before_work(railtab_program, args):
    r = run(railtab_program, *args, timeout=20)   # refused at once: no sweep, no table generation
    assert r.returncode == 1 and r.stdout == ""
    assert "refused before starting" in r.stderr and "progress" not in r.stderr


@pytest.mark.parametrize("args", [
    ["eval", "--scene", "MISSING"],
    ["generate", "MISSING", "-o", "OUT.h5"],
    ["inspect", "MISSING"],
    ["query", "MISSING", "--y", "0", "--load", "78500"],
    ["merge", "OUT.h5", "MISSING"],
    ["simulate", "MISSING", "--out", "OUT"],
    ["chart-geometry", "--scene", "MISSING", "--out", "OUT"],
    ["chart-stability", "--scene", "MISSING", "--out", "OUT"],
    ["chart-pressure", "--scene", "MISSING", "--out", "OUT"],
    ["conicity", "--scene", "MISSING", "--out", "OUT"],
    ["conicity", "--table", "MISSING", "--out", "OUT"],
    ["conicity", "--scene", SCENE, "--compare", "MISSING", "--out", "OUT"],
    ["export", "MISSING", "--csv", "-o", "OUT"],
])
def test_missing_input_is_error_1_naming_it_with_nothing_written(railtab_program, tmp_path, args):
    # README: an unreadable file is an error (1), not a usage error (2): generate, merge and simulate
    # gave 2 with CLI11's "File does not exist"; the chart commands and simulate created OUT first.
    missing, out = str(tmp_path / "no-such-input"), tmp_path / "out"
    r = run(railtab_program, *[a.replace("MISSING", missing).replace("OUT", str(out)) for a in args], timeout=20)
    assert r.returncode == 1 and r.stdout == "", (args, r.returncode, r.stderr)
    assert missing in r.stderr and r.stderr.startswith("railtab: error: "), r.stderr
    assert list(tmp_path.iterdir()) == [], list(tmp_path.iterdir())


@pytest.mark.parametrize("args", [
    ["query", "TABLE", "--y", "0", "--load", "78500", "--method", "quadratic"],
    ["query", "TABLE", "--y", "0", "--load", "78500", "--wheel", "middle"],
    ["eval", "--scene", SCENE, "--model", "hertzz"],
])
def test_value_outside_a_list_is_usage_error_2(railtab_program, stripes_table, args):
    r = run(railtab_program, *[str(stripes_table) if a == "TABLE" else a for a in args])
    assert r.returncode == 2 and r.stdout == "", (args, r.returncode, r.stderr)
    assert args[-1] in r.stderr, r.stderr


@pytest.mark.parametrize("args, message", [
    (["--duration", "-1"], "--duration: must be a number in [1e-06, 86400] s, got -1 s"),
    (["--duration", "0"], "--duration: must be a number in [1e-06, 86400] s"),   # 0 would silently run the whole route
    (["--duration", "abc"], "got 'abc'"),
    (["--threads", "-1"], "--threads: must be a whole number in [0, 1024]"),
    (["--threads", "1.5"], "got 1.5 (not a whole number)"),
    (["--post-processors", "hertz", "stripes"], "--post-processors: unknown wear post-processor 'stripes'"),
])
def test_simulate_bad_option_names_it(railtab_program, tmp_path, args, message):
    # refused while parsing the command line: no table, no output directory
    r = run(railtab_program, "simulate", str(SOURCE_DIR / "tables" / "sim" / "r600.toml"), "--out",
            str(tmp_path / "out"), *args, timeout=20)
    assert r.returncode == 2 and r.stdout == ""
    assert message in r.stderr and "179769" not in r.stderr   # no 300-digit range bound
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("threads", ["-1", "1.5", "many"])
def test_generate_bad_thread_count_names_it(railtab_program, tmp_path, threads):
    # the same check as simulate's (cli_common): a usage error naming the option, no table
    out = tmp_path / "t.h5"
    r = run(railtab_program, "generate", SCENE, "-o", str(out), "--threads", threads, timeout=20)
    assert r.returncode == 2 and r.stdout == "", (r.returncode, r.stderr)
    assert "--threads: must be a whole number in [0, 1024]" in r.stderr and "179769" not in r.stderr, r.stderr
    assert not out.exists()


def test_query_refuses_roll_on_an_equilibrium_roll_table(railtab_program, stripes_table):
    # The STRIPES table's roll follows the equilibrium: --roll would be silently ignored.
    r = run(railtab_program, "query", str(stripes_table), "--y", "0.001", "--load", "70000", "--roll", "0.005")
    assert r.returncode == 1 and r.stdout == "", (r.returncode, r.stdout)
    assert "--roll" in r.stderr and str(stripes_table) in r.stderr and "equilibrium" in r.stderr, r.stderr
    ok = run(railtab_program, "query", str(stripes_table), "--y", "0.001", "--load", "70000")
    assert ok.returncode == 0 and "query status" in ok.stdout


def test_conicity_json_from_scene_and_table(railtab_program, stripes_table):
    # docs/conicity.md: JSON with amplitude_m and equivalent_conicity; the STRIPES table's 0.5 mm
    # tread grid gives the scene's value at 3 mm to 0.005 (docs/validation/conicity.md: 0.184 both)
    import json
    results = []
    for source in (["--scene", SCENE], ["--table", str(stripes_table)]):
        r = run(railtab_program, "conicity", *source, "--amplitudes", "0.001,0.003", "--json", timeout=120)
        assert r.returncode == 0 and r.stderr == "", r.stderr
        j = json.loads(r.stdout)
        assert j["amplitude_m"] == [0.001, 0.003]
        assert len(j["equivalent_conicity"]) == 2 and len(j["equivalent_conicity_regression"]) == 2
        results.append(j["equivalent_conicity"][1])
    assert 0.15 < results[0] < 0.22, results
    assert abs(results[0] - results[1]) < 0.005, results


@pytest.mark.parametrize("args, code, message", [
    (["--amplitudes", "abc"], 2, "abc"),
    (["--amplitudes", "-0.001"], 2, "--amplitudes: value 1 of '-0.001': must be a number in [1e-06, 0.1] m"),
    (["--table", "T.h5"], 2, "--table"),     # --scene and --table exclude each other
])
def test_conicity_bad_input_names_it(railtab_program, args, code, message):
    r = run(railtab_program, "conicity", "--scene", SCENE, *args, timeout=60)
    assert r.returncode == code and r.stdout == "", (r.returncode, r.stderr)
    assert message in r.stderr, r.stderr
