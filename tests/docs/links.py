#!/usr/bin/env python3
"""Every page README.md and docs/ point to exists.

Reads README.md and docs/**/*.md for markdown links `[text](path)` and for page names written
in the text (`docs/<name>.md`, `bench/<name>.md`); each must name a file of the project
(anchors and web addresses are not checked). Every page of docs/ is in the README's docs index
and in docs/README.md, and every study of docs/notes/ in docs/README.md. Fails naming the file,
line and missing target or page.
Usage: python3 tests/docs/links.py [project root]   (ctest: docs.links)
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
me = "tests/docs/links.py"

link = re.compile(r"\]\(([^)\s#]+)(?:#[^)]*)?\)")
named = re.compile(r"(?<![\w/.-])((?:docs|bench)/[A-Za-z0-9_/.-]+\.md)")
failures = []
checked = 0
for page in [root / "README.md"] + sorted((root / "docs").rglob("*.md")):
    in_code = False
    for number, line in enumerate(page.read_text().splitlines(), 1):
        if line.lstrip().startswith("```"):
            in_code = not in_code
            continue
        if in_code:
            continue
        targets = []
        for target in link.findall(line):
            if re.match(r"[a-z]+:", target):
                continue  # a web address
            targets.append(((page.parent / target).resolve(), target))
        for target in named.findall(line):
            targets.append(((root / target).resolve(), target))
        for path, text in targets:
            checked += 1
            relative = path.relative_to(root) if path.is_relative_to(root) else path
            if not path.exists():
                failures.append(f"{page.relative_to(root)}:{number}: {text}: no such file")

# The indexes: the README's "## Docs" list and docs/README.md.
readme = (root / "README.md").read_text()
index_at = readme.find("\n## Docs")
if index_at < 0:
    failures.append("README.md: no \"## Docs\" section (the index of the docs pages)")
readme_index = readme[index_at:] if index_at >= 0 else ""
docs_index = (root / "docs/README.md").read_text() if (root / "docs/README.md").exists() else ""
for page in sorted((root / "docs").glob("*.md")):
    name = page.name
    if name == "README.md":
        continue
    if f"(docs/{name})" not in readme_index:
        failures.append(f"README.md: the docs index (## Docs) does not list docs/{name}")
    if f"({name})" not in docs_index:
        failures.append(f"docs/README.md: does not list {name}")
for page in sorted((root / "docs/notes").glob("*.md")):
    if f"(notes/{page.name})" not in docs_index:
        failures.append(f"docs/README.md: does not list notes/{page.name}")
    if not page.read_text().startswith("# Study: "):
        failures.append(f"docs/notes/{page.name}:1: a study's first line is \"# Study: <what>\"")

for failure in failures:
    print(f"{me}: {failure}", file=sys.stderr)
if failures:
    sys.exit(f"{me}: {len(failures)} problem(s): links to missing files or pages missing from the indexes")
print(f"{me}: {checked} links and page names in README.md and docs/ name existing files")
