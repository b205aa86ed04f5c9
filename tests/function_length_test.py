# SPDX-License-Identifier: Apache-2.0
"""No function in generator/ is longer than 150 lines (a function that long mixes jobs: split it by
job). Reads the sources without compiling: comments, strings and preprocessor lines are blanked, then
braces are matched; a brace block at namespace or class level whose head ends in a parameter list
(with any qualifiers) is a function, counted from the first line of its head to its closing brace.
Lambdas and local classes count toward the function that holds them.
Usage: function_length_test.py SOURCE_DIR [--list N]   (--list N: print every function over N lines)"""
import re
import sys
from pathlib import Path

SCANNED = ["generator"]
LIMIT = 150


def blank_code(text):
    """The text with comments, string and character literals and preprocessor lines replaced by
    spaces (newlines kept, so line numbers stay)."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            # A preprocessor line, with its continuations.
            while i < n and text[i] != "\n":
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append(" \n")
                    i += 2
                    continue
                out.append(" ")
                i += 1
            continue
        if c == "/" and text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if c == "/" and text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        raw = re.match(r'R"([^()\\ ]{0,16})\(', text[i:i + 20]) if c == "R" else None
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            close = ")" + raw.group(1) + '"'
            end = text.find(close, i + raw.end())
            end = n if end < 0 else end + len(close)
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        if c in "\"'":
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            end = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:end]))
            i = end
            continue
        out.append(c)
        if c == "\n":
            at_line_start = True
        elif not c.isspace():
            at_line_start = False
        i += 1
    return "".join(out)


QUALIFIERS = r"(\s*(const|noexcept(\s*\([^()]*\))?|override|final|volatile|&&?|mutable|->\s*[\w:<>,\s*&]+))*"
FUNCTION_HEAD = re.compile(r"\)" + QUALIFIERS + r"\s*$")
TYPE_HEAD = re.compile(r"\b(namespace|class|struct|union|enum)\b|\bextern\s*$")


def functions(text):
    """(name, first line, last line) of every function defined in the source text."""
    code = blank_code(text)
    found = []
    stack = []  # per open brace: "scope" (namespace/class), "function", "inner" or "initialiser"
    head_start = 0  # where the text since the last ; { or } begins
    for pos, c in enumerate(code):
        if c == ";":
            head_start = pos + 1
        elif c == "{":
            head = code[head_start:pos]
            if any(kind in ("function", "inner") for kind, _, _ in stack):
                stack.append(("inner", 0, ""))
            elif FUNCTION_HEAD.search(head) or (re.search(r"\)\s*:", head) and re.search(r"\}\s*$", head)):
                first = head_start + len(head) - len(head.lstrip())
                line = code.count("\n", 0, first) + 1
                name = re.search(r"([~\w:]+(operator\s*\S+)?)\s*\((?![^()]*\()", head)
                stack.append(("function", line, name.group(1) if name else "?"))
            elif TYPE_HEAD.search(head) and "=" not in head:
                stack.append(("scope", 0, ""))
            else:
                # A brace initialiser outside any function (a member initialiser list's x_{a}, an
                # initialised variable): the head goes on through it.
                stack.append(("initialiser", 0, ""))
                continue
            head_start = pos + 1
        elif c == "}":
            if stack:
                kind, line, name = stack.pop()
                if kind == "function":
                    found.append((name, line, code.count("\n", 0, pos) + 1))
                if kind == "initialiser":
                    continue
            head_start = pos + 1
    return found


def main():
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = Path(sys.argv[1])
    limit = LIMIT
    listing = None
    if len(sys.argv) == 4 and sys.argv[2] == "--list":
        listing = int(sys.argv[3])
    # The parser sees a long function through a comment's brace, a string's brace and an initialiser.
    probe = ('namespace a {\nstruct S { int x{1}; };\nS::S(int v) : x_{v} {}\nint f(int a) const {\n'
             + '  g("}"); // }\n' * LIMIT + "}\n}\n")
    if [(n, b, e) for n, b, e in functions(probe) if e - b + 1 > LIMIT] != [("f", 4, LIMIT + 5)]:
        print(f"function_length_test: the parser misreads a known function: {functions(probe)}")
        return 1
    scanned = 0
    over = []
    for folder in SCANNED:
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h"):
                continue
            for name, first, last in functions(path.read_text(encoding="utf-8", errors="replace")):
                scanned += 1
                length = last - first + 1
                if listing is not None and length > listing:
                    print(f"{length:5d} {path.relative_to(root)}:{first} {name}")
                if length > limit:
                    over.append(f"{path.relative_to(root)}:{first}: {name} is {length} lines (limit {limit})")
    # A scan that finds no function has lost its way (moved folder, broken parser): fail, not pass.
    if scanned < 100:
        print(f"function_length_test: only {scanned} functions found under {SCANNED}: the scan is broken")
        return 1
    for line in over:
        print(line)
    print(f"function_length_test: {scanned} functions in {', '.join(SCANNED)}/, {len(over)} over {limit} lines")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
