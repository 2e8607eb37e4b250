#!/usr/bin/env python3
"""Every C function of <fluid/c.h> is listed exactly once in the C API docs' function tables.

Reads the declarations of c/include/fluid/c.h (lines starting `FLUID_C_API`) and the function
tables of docs/c_api*.md (tables whose header's first cell is `function`; a row's first cell
names one or more functions in backticks). Fails, naming the file and line, for a declared
function no table lists, one listed twice, or a listed name that c.h does not declare.
Usage: python3 tests/docs/c_functions.py [project root]   (ctest: docs.c_functions)
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
me = "tests/docs/c_functions.py"
header = root / "c/include/fluid/c.h"

declared = {}
for number, line in enumerate(header.read_text().splitlines(), 1):
    match = re.match(r"FLUID_C_API\b.*?\b(fluid_[a-z0-9_]+)\s*\(", line)
    if match:
        declared.setdefault(match.group(1), number)
if not declared:
    sys.exit(f"{me}: c/include/fluid/c.h: no FLUID_C_API declaration found")

pages = sorted((root / "docs").glob("c_api*.md"))
if not pages:
    sys.exit(f"{me}: no docs/c_api*.md page found")

listed = {}  # name -> [(page, line)]
for page in pages:
    in_function_table = False
    for number, line in enumerate(page.read_text().splitlines(), 1):
        if not line.startswith("|"):
            in_function_table = False
            continue
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if re.fullmatch(r"-+:?", cells[0].replace(":", "-")) or set(cells[0]) <= set("-: "):
            continue  # the separator row
        if not in_function_table and cells[0] == "function":
            in_function_table = True
            continue
        if in_function_table:
            for name in re.findall(r"`(fluid_[a-z0-9_]+)`", cells[0]):
                listed.setdefault(name, []).append((page.relative_to(root), number))

failures = []
for name, places in sorted(listed.items()):
    if name not in declared:
        page, number = places[0]
        failures.append(f"{page}:{number}: `{name}` is listed but c/include/fluid/c.h declares no such function")
    if len(places) > 1:
        where = ", ".join(f"{page}:{number}" for page, number in places)
        failures.append(f"{places[1][0]}:{places[1][1]}: `{name}` is listed {len(places)} times ({where}); list it once")
for name, number in sorted(declared.items(), key=lambda item: item[1]):
    if name not in listed:
        failures.append(f"c/include/fluid/c.h:{number}: `{name}` is in no function table of docs/c_api*.md")

for failure in failures:
    print(f"{me}: {failure}", file=sys.stderr)
if failures:
    sys.exit(f"{me}: {len(failures)} problem(s) between c/include/fluid/c.h and the C API docs' function tables")
print(f"{me}: the {len(declared)} functions of c/include/fluid/c.h are each listed once in {', '.join(str(p.relative_to(root)) for p in pages)}")
