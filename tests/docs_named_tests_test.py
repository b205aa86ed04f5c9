# SPDX-License-Identifier: Apache-2.0
"""Checks that every test docs/reliability.md names exists, so its threat model and its table of
guarantees cannot point at a test that was renamed or never written. In code spans it finds:
GoogleTest names `Suite.Name` and `Suite.*` (a TEST, TEST_F or TEST_P in tests/), pytest
functions `test_name` or `file.py::test_name` (a def in python/tests/; or a test program of that
name, an add_executable), CTest names after the
word CTest (an add_test in a CMakeLists.txt), libFuzzer targets `fuzz_name` (fuzz/fuzz_name.cpp)
and test files under tests/, python/tests/, scripts/ and fuzz/.

Usage: python3 tests/docs_named_tests_test.py [REPOSITORY_ROOT]   (exit status 1 and one line
per missing test; CTest runs it as docs.named_tests)."""
import pathlib
import re
import sys

CODE = re.compile(r"`([^`\n]+)`")
GTEST = re.compile(r"^([A-Z]\w*)\.([A-Z]\w*|\*)$")
PYTEST = re.compile(r"^(?:([\w/]+\.py)::)?(test_\w+)$")
FUZZ = re.compile(r"^fuzz_\w+$")
TEST_FILE = re.compile(r"^(tests|python/tests|scripts|fuzz)/[\w/.-]+\.(py|cpp|sh)$")
CTEST = re.compile(r"CTests?\s+`([\w.]+)`")


def main(root):
    doc = root / "docs" / "reliability.md"
    text = doc.read_text(encoding="utf-8")
    cpp = "\n".join(p.read_text(encoding="utf-8", errors="replace") for p in (root / "tests").rglob("*.cpp"))
    py_files = {p.relative_to(root).as_posix(): p.read_text(encoding="utf-8")
                for p in (root / "python" / "tests").glob("*.py")}
    cmake = "\n".join(p.read_text(encoding="utf-8") for p in root.rglob("CMakeLists.txt")
                      if "build" not in p.relative_to(root).parts)
    problems, checked = [], 0
    for n, line in enumerate(text.splitlines(), 1):
        where = f"docs/reliability.md:{n}"
        for name in CTEST.findall(line):
            checked += 1
            if not re.search(r"add_test\(\s*NAME\s+" + re.escape(name) + r"\s", cmake):
                problems.append(f"{where}: CTest {name}: no add_test(NAME {name} ...) in any CMakeLists.txt")
        for span in CODE.findall(line):
            m = GTEST.match(span)
            if m:
                checked += 1
                suite, test = m.groups()
                pattern = (r"\bTEST(_F|_P)?\(\s*" + suite + r"\s*,\s*" +
                           (r"\w+" if test == "*" else test + r"\s*\)"))
                if not re.search(pattern, cpp):
                    problems.append(f"{where}: GoogleTest {span}: no such test in tests/")
                continue
            m = PYTEST.match(span)
            if m:
                checked += 1
                file, func = m.groups()
                if file and "/" not in file:
                    file = "python/tests/" + file
                files = [file] if file else list(py_files)
                if re.search(r"add_executable\(\s*" + func + r"\s", cmake) and not file:
                    continue  # a test program (e.g. test_lookup, the lookup's GoogleTest binary)
                if not any(re.search(r"^def " + func + r"\(", py_files.get(f, ""), re.M) for f in files):
                    problems.append(f"{where}: pytest {span}: no def {func} in "
                                    f"{file or 'python/tests/*.py'}")
                continue
            if FUZZ.match(span):
                checked += 1
                if not (root / "fuzz" / (span + ".cpp")).is_file():
                    problems.append(f"{where}: libFuzzer target {span}: no fuzz/{span}.cpp")
                continue
            m = TEST_FILE.match(span.split("::")[0])
            if m:
                checked += 1
                if not (root / span.split("::")[0]).is_file():
                    problems.append(f"{where}: {span}: no such file")
    if checked < 20:
        problems.append(f"docs/reliability.md: only {checked} test names found: has the page's format changed?")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()))
