#!/usr/bin/env python3
"""docs/levels.md's table of shipped levels is levels/*.json, each once, with its name.

The table follows the line `<!-- shipped levels: checked by tests/docs/levels_table.py -->`;
its first cell is the level file (`name.json`) and its second the level's title (the file's
"name"). Fails, naming the line, for a row whose file does not exist, whose title differs, a
file listed twice, or a level file the table leaves out.
Usage: python3 tests/docs/levels_table.py [project root]   (ctest: docs.levels_table)
"""
import json
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
me = "tests/docs/levels_table.py"
marker = "<!-- shipped levels: checked by tests/docs/levels_table.py -->"
page = root / "docs/levels.md"

titles = {path.name: json.loads(path.read_text())["name"] for path in (root / "levels").glob("*.json")}
lines = page.read_text().splitlines()
if marker not in lines:
    sys.exit(f"{me}: docs/levels.md: the line {marker} is missing")

failures = []
rows = {}
start = lines.index(marker) + 1
number = start
while number < len(lines) and not lines[number].startswith("|"):
    number += 1
header = True
for number in range(number, len(lines)):
    line = lines[number]
    if not line.startswith("|"):
        break
    if header or set(line) <= set("|-: "):
        header = False
        continue
    where = f"docs/levels.md:{number + 1}"
    cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
    match = re.fullmatch(r"`(?:levels/)?([A-Za-z0-9_.-]+\.json)`", cells[0])
    if not match:
        failures.append(f"{where}: the first cell \"{cells[0]}\" is not a level file (`name.json`)")
        continue
    name = match.group(1)
    title = cells[1] if len(cells) > 1 else ""
    if name in rows:
        failures.append(f"{where}: {name} is listed again (first at docs/levels.md:{rows[name]})")
        continue
    rows[name] = number + 1
    if name not in titles:
        failures.append(f"{where}: {name}: there is no levels/{name}")
    elif title != titles[name]:
        failures.append(f"{where}: {name}: the title \"{title}\" is not the file's name \"{titles[name]}\"")
for name in sorted(set(titles) - set(rows)):
    failures.append(f"docs/levels.md:{start}: levels/{name} (\"{titles[name]}\") is missing from the table of shipped levels")

for failure in failures:
    print(f"{me}: {failure}", file=sys.stderr)
if failures:
    sys.exit(f"{me}: {len(failures)} difference(s) between docs/levels.md's table and levels/*.json")
print(f"{me}: docs/levels.md lists the {len(titles)} files of levels/ with their names")
