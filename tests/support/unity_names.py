#!/usr/bin/env python3
"""The test executables are unity builds (tests/CMakeLists.txt): each compiles its files a few
at a time as one file, so two files of one executable must not define the same name at
namespace scope. The same signature would fail to compile, but two overloads of one name would
compile, and a call in one file could silently take the other file's function. This check
fails on any name (function, type, constant, alias or macro) defined at the start of a line in
two files of one executable, and names both places; share the helper in a support header or
name each for what it does.

    unity_names.py MANIFEST   lines "target<TAB>file;file;..." (written by tests/CMakeLists.txt)
"""
import re
import sys

KEYWORDS = {"return", "else", "if", "for", "while", "switch", "do", "case", "default",
            "TEST_CASE", "SECTION", "SCENARIO", "TEMPLATE_TEST_CASE", "main", "namespace",
            "using", "struct", "class", "enum", "union", "template", "operator"}

PATTERNS = [
    # A function at namespace scope: a type, then the name and '(' on the first line.
    ("function", re.compile(
        r"^(?:static |inline |constexpr |\[\[nodiscard\]\] )*"
        r"[A-Za-z_][\w:<>, \t\*&]*?[ \t\*&]([A-Za-z_]\w*)\(", re.M)),
    ("type", re.compile(r"^(?:struct|class|union|enum(?: class)?) ([A-Za-z_]\w*)\b", re.M)),
    ("constant", re.compile(
        r"^(?:static |inline )*(?:constexpr|const) [\w:<>, ]+?[ \*&]([A-Za-z_]\w*) *(?:=|\{|\[)",
        re.M)),
    ("alias", re.compile(r"^using ([A-Za-z_]\w*) =", re.M)),
    ("macro", re.compile(r"^#define ([A-Za-z_]\w*)", re.M)),
]


def names_in(path):
    text = open(path, encoding="utf-8").read()
    found = {}
    for kind, pattern in PATTERNS:
        for match in pattern.finditer(text):
            name = match.group(1)
            if name in KEYWORDS:
                continue
            line = text.count("\n", 0, match.start()) + 1
            found.setdefault(name, (kind, line))
    return found


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    failures = 0
    targets = 0
    for row in open(sys.argv[1], encoding="utf-8"):
        row = row.rstrip("\n")
        if not row:
            continue
        target, files = row.split("\t")
        sources = [f for f in files.split(";") if f.endswith((".cpp", ".cc", ".c"))]
        targets += 1
        where = {}
        for path in sources:
            for name, (kind, line) in names_in(path).items():
                where.setdefault(name, []).append((path, line, kind))
        for name, places in sorted(where.items()):
            if len(places) > 1:
                failures += 1
                spots = ", ".join(f"{p}:{line} ({kind})" for p, line, kind in places)
                print(f"unity_names.py: {target}: '{name}' is defined in {len(places)} files: "
                      f"{spots}", file=sys.stderr)
    if failures:
        print(f"unity_names.py: {failures} name(s) defined twice in one test executable",
              file=sys.stderr)
        return 1
    print(f"unity_names.py: no name defined twice in the files of any of {targets} test "
          "executables")
    return 0


if __name__ == "__main__":
    sys.exit(main())
