#!/usr/bin/env python3
"""<vds/vds.h> is the manual: every public free function and every public
class or struct of every layer's installed headers must be named in it.

Reads the headers under every include/ of vds/ (the installed ones; <vds/detail/...>
lives elsewhere and is not installed), takes the names declared at namespace
scope (declarations start in column 0 in this code base: free functions,
classes, structs, enums), and fails listing every name the manual does not
mention as a whole word.

With `headers`, checks instead that every <vds/...> header a comment (or an
include) names in the sources, tools, samples, tests, benchmarks and
bindings exists: a public header of some layer (wherever its folder holds
it) or an internal <vds/detail/...> one. Placeholders such as <vds/gl/...>
are skipped.

    check_manual.py SOURCE_DIR [names|headers]
"""
import pathlib
import re
import sys

KEYWORDS = {"if", "for", "while", "return", "switch", "sizeof", "operator", "static_assert", "decltype", "alignof"}
FUNCTION = re.compile(r"^(?:template <[^>]*>\s*)?(?:\[\[\w+\]\]\s*)?(?:inline\s+|constexpr\s+|static\s+)*"
                      r"[A-Za-z_][\w:<>,\s\*&]*?[\s\*&]([A-Za-z_]\w*)\s*\(")
TYPE = re.compile(r"^(?:template <[^>]*>\s*)?(?:class|struct|enum class|enum)\s+([A-Za-z_]\w*)\s*(?:final\s*)?[:{]")


def public_names(source: pathlib.Path):
    names = {}
    for header in sorted(source.glob("vds/**/include/vds/**/*.h")):
        if "detail" in header.parts:
            continue
        text = header.read_text()
        # Internals the public types need to hold (namespace detail) are not API.
        text = re.sub(r"namespace detail \{.*?\} // namespace detail", "", text, flags=re.S)
        # Drop comments, so commented-out code or prose is not a declaration.
        text = re.sub(r"//[^\n]*", "", text)
        text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
        for line in text.splitlines():
            if not line or line[0].isspace() or line.startswith("#"):
                continue
            for pattern in (TYPE, FUNCTION):
                m = pattern.match(line)
                if m and m.group(1) not in KEYWORDS and not m.group(1).startswith("VDS_"):
                    names.setdefault(m.group(1), header.relative_to(source))
                    break
    return names


NAMED_HEADER = re.compile(r"<(vds/[\w/.]+\.h)>")
SCANNED = ("vds", "tools", "samples", "tests", "bench", "python/src", "fuzz")


def include_name(header: pathlib.Path, source: pathlib.Path):
    """The name a header is included by: its path from the last folder named vds."""
    parts = header.relative_to(source).parts
    last = max(i for i, part in enumerate(parts) if part == "vds")
    return "/".join(parts[last:])


def check_named_headers(source: pathlib.Path):
    existing = {include_name(h, source) for h in (source / "vds").rglob("*.h")}
    wrong = []
    for folder in SCANNED:
        for path in sorted((source / folder).rglob("*")):
            if path.suffix not in (".h", ".cpp", ".py", ".glsl", ".comp", ".vert", ".frag") or not path.is_file():
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                for name in NAMED_HEADER.findall(line):
                    if name not in existing:
                        wrong.append(f"  {path.relative_to(source)}:{number}: <{name}>")
    if wrong:
        print(f"{len(wrong)} names of <vds/...> headers that do not exist:")
        print("\n".join(wrong))
        return 1
    print(f"every <vds/...> header named in {', '.join(SCANNED)} exists ({len(existing)} headers)")
    return 0


def check_manual(source: pathlib.Path):
    manual = (source / "vds/core/include/vds/vds.h").read_text()
    names = public_names(source)
    missing = sorted((str(h), n) for n, h in names.items() if not re.search(r"\b" + re.escape(n) + r"\b", manual))
    if missing:
        print(f"<vds/vds.h> does not name {len(missing)} of {len(names)} public names:")
        for header, name in missing:
            print(f"  {name:32} {header}")
        return 1
    print(f"<vds/vds.h> names all {len(names)} public functions and types")
    return 0


def main():
    source = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    mode = sys.argv[2] if len(sys.argv) > 2 else "names"
    return check_named_headers(source) if mode == "headers" else check_manual(source)


if __name__ == "__main__":
    sys.exit(main())
