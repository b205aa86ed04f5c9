# SPDX-License-Identifier: Apache-2.0
"""Every file railtab writes goes through its one output path (generator/table/output_file.hpp):
write_text_file, OutputFile, open_output_to_continue. This test lists every writer in the product's
code (generator/, src/, lookup/, python/: fopen, ofstream, H5Fcreate, open with a write flag,
rename, copy, truncate; Python's open for writing, write_text, shutil, os.replace ...) and fails
when one is not among the few inside that path, each allowed with its reason. Tests, benchmarks,
fuzz targets and scripts/ are tools around the product and are not scanned.
Usage: output_paths_test.py SOURCE_DIR"""
import re
import sys
from pathlib import Path

SCANNED = ["generator", "src", "lookup", "python/src", "python/railtab"]

CPP_WRITERS = [
    r"\bfopen\s*\(", r"\bfreopen\s*\(", r"\bfdopen\s*\(", r"(?<![i])\bofstream\b", r"(?<![io])\bfstream\b",
    r"\bH5Fcreate\s*\(", r"\bH5Fopen\s*\([^;]*RDWR", r"\bcreat\s*\(", r"\brename(at)?\s*\(",
    r"\bcopy_file\b", r"\bfilesystem::copy\b", r"\bfs::copy\b", r"\bresize_file\b", r"\bf?truncate\s*\(",
    r"\bmkstemp\b", r"\btmpfile\s*\(", r"\bcreate_(hard_link|symlink|directory_symlink)\s*\(",
    r"\bopen\s*\([^;]*\bO_(CREAT|WRONLY|RDWR|TRUNC|APPEND)\b",
]
PY_WRITERS = [
    r"\bopen\s*\([^)]*['\"][rb]*[wax+][b+t]*['\"]", r"\.write_(text|bytes)\s*\(", r"\bshutil\.",
    r"\bos\.(rename|replace|link|symlink|truncate)\s*\(", r"\.tofile\s*\(", r"\bnp\.save", r"\bsavetxt\s*\(",
    r"\bh5py\.File\s*\([^)]*['\"][wax]",
]

# (file, what the line holds, how many such lines, why it is allowed)
ALLOWED = [
    ("generator/table/output_file.cpp", "O_CREAT | O_EXCL | O_NOFOLLOW", 2,
     "the output path itself: the temporary created exclusively, the directory probe"),
    ("generator/table/output_file.cpp", "O_RDWR | O_NOFOLLOW", 2,
     "the output path itself: a stale temporary checked before removal, an output a run continues"),
    ("generator/table/output_file.cpp", "::rename(", 1, "the output path itself: the commit"),
    ("generator/table/table_writer.cpp", "H5Fcreate(", 1,
     "HDF5 writes the table into OutputFile's temporary (write_table), renamed by its commit"),
    ("generator/engine/checkpoint.cpp", "::ftruncate(", 1,
     "the checkpoint's torn tail cut on the descriptor open_output_to_continue checked and locked"),
]


def strip_comment(line, python):
    return line.split("#", 1)[0] if python else line.split("//", 1)[0]


def writers(source):
    found = []
    for root in SCANNED:
        for path in sorted((source / root).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h", ".c", ".py") or "tests" in path.relative_to(source).parts:
                continue
            python = path.suffix == ".py"
            patterns = PY_WRITERS if python else CPP_WRITERS
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                code = strip_comment(line, python)
                if code.lstrip().startswith("#include"):
                    continue
                if any(re.search(p, code) for p in patterns):
                    found.append((path.relative_to(source).as_posix(), number, line.strip()))
    return found


def main():
    source = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[1]
    found = writers(source)
    print(f"{len(found)} writer(s) in {', '.join(SCANNED)}:")
    for path, number, line in found:
        print(f"  {path}:{number}: {line}")
    failures = []
    used = [0] * len(ALLOWED)
    for path, number, line in found:
        match = [i for i, (f, text, _, _) in enumerate(ALLOWED) if f == path and text in line]
        if match:
            used[match[0]] += 1
        else:
            failures.append(f"{path}:{number}: writes outside the output path (use write_text_file or OutputFile "
                            f"of generator/table/output_file.hpp): {line}")
    for (path, text, count, why), n in zip(ALLOWED, used):
        if n != count:
            failures.append(f"{path}: {n} line(s) with '{text}', {count} allowed ({why}): a new writer there, or "
                            f"this list is out of date")
    for f in failures:
        print("FAIL " + f)
    print("output paths: " + ("FAIL" if failures else "PASS"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
