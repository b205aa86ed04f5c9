# SPDX-License-Identifier: Apache-2.0
"""Checks the documentation's links: every relative link and image in README.md and docs/**/*.md
must name a file or folder of the repository, and a #fragment must name a heading (GitHub's
anchor of it) or an <a id="..."> of the target page; every page of docs/ must be reachable from
the index docs/README.md. Also refuses absolute links, and text that
names an issue or session number or a scratch folder (/work/..., /tmp/...): the docs speak to
users about the project as it is (docs/README.md is the index).

Usage: python3 tests/docs_links_test.py [REPOSITORY_ROOT]   (exit status 1 and one line per
problem when something is wrong; CTest runs it as docs.links)."""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
EXPLICIT_ANCHOR = re.compile(r"<a\s+(?:id|name)=\"([^\"]+)\"")
FENCE = re.compile(r"^\s*(```|~~~)")
FORBIDDEN = [
    (re.compile(r"\b(issue|session)\s+#?[0-9]+", re.IGNORECASE), "names an issue or session number"),
    (re.compile(r"(?<![\w.~-])/(work|tmp)/"), "names a scratch folder (an absolute /work or /tmp path)"),
]


def strip_code(lines):
    """The lines outside fenced code blocks, inline code spans blanked (line numbers kept)."""
    out, fenced = [], False
    for line in lines:
        if FENCE.match(line):
            fenced = not fenced
            out.append("")
            continue
        out.append("" if fenced else re.sub(r"`[^`]*`", "``", line))
    return out


def slug(text):
    """GitHub's anchor of a heading: markup and punctuation dropped, lower case, spaces to '-'."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link keeps its text
    text = re.sub(r"<[^>]+>", "", text).strip().lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, seen = set(), {}
        for line in strip_code(path.read_text(encoding="utf-8").splitlines()):
            found.update(EXPLICIT_ANCHOR.findall(line))
            m = HEADING.match(line)
            if m:
                base = slug(m.group(2))
                n = seen.get(base, 0)
                seen[base] = n + 1
                found.add(base if n == 0 else f"{base}-{n}")
        # headings inside code spans are rare; read the raw text too for explicit anchors
        found.update(EXPLICIT_ANCHOR.findall(path.read_text(encoding="utf-8")))
        cache[path] = found
    return cache[path]


def check(root):
    problems = []
    pages = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    for page in pages:
        raw = page.read_text(encoding="utf-8").splitlines()
        where = page.relative_to(root)
        for number, (line, raw_line) in enumerate(zip(strip_code(raw), raw), start=1):
            for pattern, why in FORBIDDEN:
                if pattern.search(raw_line):
                    problems.append(f"{where}:{number}: {why}: {raw_line.strip()[:100]}")
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                if target.startswith("/"):
                    problems.append(f"{where}:{number}: absolute link '{target}' (use a relative one)")
                    continue
                path_part, _, fragment = target.partition("#")
                dest = (page.parent / path_part).resolve() if path_part else page
                if not dest.exists():
                    problems.append(f"{where}:{number}: dead link '{target}': no {dest.relative_to(root.resolve()) if dest.is_relative_to(root.resolve()) else dest}")
                    continue
                if root.resolve() not in dest.parents and dest != root.resolve():
                    problems.append(f"{where}:{number}: link '{target}' leaves the repository")
                    continue
                if fragment and dest.is_file() and dest.suffix == ".md" and fragment not in anchors(dest):
                    problems.append(f"{where}:{number}: link '{target}': no heading or anchor '#{fragment}' in {dest.name}")
    problems += unreachable(root, pages)
    return pages, problems


def unreachable(root, pages):
    """Every page of docs/ must be reachable from the index docs/README.md by links."""
    index = root / "docs" / "README.md"
    if not index.exists():
        return ["docs/README.md: the index is missing"]
    seen, todo = {index.resolve()}, [index]
    while todo:
        page = todo.pop()
        for line in strip_code(page.read_text(encoding="utf-8").splitlines()):
            for target in LINK.findall(line):
                path_part = target.partition("#")[0]
                if not path_part or re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("/"):
                    continue
                dest = (page.parent / path_part).resolve()
                if dest.suffix == ".md" and dest.is_file() and dest not in seen and (root / "docs").resolve() in dest.parents:
                    seen.add(dest)
                    todo.append(dest)
    return [f"{p.relative_to(root)}: not reachable from docs/README.md (add it to the index)"
            for p in pages if (root / "docs").resolve() in p.resolve().parents and p.resolve() not in seen]


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1])
    pages, problems = check(root.resolve())
    for p in problems:
        print(p)
    print(f"docs links: {len(pages)} pages, {len(problems)} problems: {'FAIL' if problems else 'PASS'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
