#!/usr/bin/env python3
"""Every link of README.md and docs/*.md into a Markdown file of the project
lands on that file, and on a heading of it where the link names one (the
anchor GitHub makes: lower case, punctuation dropped, spaces as hyphens, a
repeated heading numbered -1, -2, ...); and docs/benchmarks.md, the page of
today's figures, stays short enough to read (at most 600 lines).

    check_doc_links.py SOURCE_DIR
"""
import pathlib
import re
import sys
import unicodedata

MAX_BENCHMARK_LINES = 600
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+\.md)(#[^)\s]*)?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def slug(heading: str) -> str:
    text = re.sub(r"`|\*\*|__", "", heading).strip().lower()
    kept = (c for c in text if c in " -" or unicodedata.category(c)[0] in "LMN" or unicodedata.category(c) == "Pc")
    return "".join(kept).replace(" ", "-")


def anchors(page: pathlib.Path):
    seen, found, fenced = {}, set(), False
    for line in page.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fenced = not fenced
        match = None if fenced else HEADING.match(line)
        if match:
            base = slug(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else "%s-%d" % (base, count))
    return found


def main(root: pathlib.Path) -> int:
    failures = []
    pages = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    for page in pages:
        for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
            for target, anchor in LINK.findall(line):
                if "://" in target:
                    continue
                path = (page.parent / target).resolve()
                where = "%s:%d: %s%s" % (page.relative_to(root), number, target, anchor)
                if not path.is_file():
                    failures.append(where + ": no such file")
                elif anchor and anchor[1:] not in anchors(path):
                    failures.append(where + ": no such heading")
    lines = len((root / "docs" / "benchmarks.md").read_text(encoding="utf-8").splitlines())
    if lines > MAX_BENCHMARK_LINES:
        failures.append("docs/benchmarks.md: %d lines, more than %d" % (lines, MAX_BENCHMARK_LINES))
    for failure in failures:
        print(failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1])))
