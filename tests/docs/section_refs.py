#!/usr/bin/env python3
"""The code's pointers into the docs lead somewhere: every `docs/PAGE.md, "Section"` (or
`bench/PAGE.md, "Section"`) written in a source file, a script or a CMake file names a page that
exists and a section whose title the page holds (a heading or a bold item). A page split or a heading
renamed fails here, naming the file and line to fix.

    python3 tests/docs/section_refs.py [SOURCE_DIR]
"""
import os
import re
import subprocess
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
os.chdir(root)
files = subprocess.run(["git", "ls-files"], capture_output=True, text=True, check=False).stdout.split()
if not files:  # not a git checkout: walk the tree
    files = [os.path.relpath(os.path.join(d, f)) for d, _, fs in os.walk(".") if "/build" not in d
             and "/.git" not in d for f in fs]
suffixes = (".cpp", ".h", ".c", ".inc", ".sh", ".py", ".cmake", "CMakeLists.txt")
# The page, an optional comma, then the quoted section, which may run on over a comment line.
ref = re.compile(r'((?:docs|bench)/[a-z_/]+\.md),?[ \t]*\(?"((?:[^"\n]|\n[ \t]*(?://+|#+|\*)[ \t]*)+)"')
cont = re.compile(r"\s*\n[ \t]*(?://+|#+|\*)[ \t]*")

texts = {}
def page_text(page):
    if page not in texts:
        with open(page, encoding="utf-8") as f:
            texts[page] = re.sub(r"\s+", " ", f.read()).lower()
    return texts[page]

failures = []
for name in files:
    if not name.endswith(suffixes) or name.startswith("tests/docs/"):
        continue
    try:
        with open(name, encoding="utf-8") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError):
        continue
    for m in ref.finditer(text):
        page, section = m.group(1), cont.sub(" ", m.group(2)).strip()
        line = text.count("\n", 0, m.start()) + 1
        if not os.path.isfile(page):
            failures.append(f"{name}:{line}: {page} does not exist")
            continue
        # Headings and bold items, the forms a section takes; a section's first words suffice.
        probe = re.sub(r"\s+", " ", section).lower().rstrip(".:")
        if probe not in page_text(page):
            failures.append(f'{name}:{line}: {page} has no section "{section}"')

for f in failures:
    print(f)
if failures:
    print(f"section_refs: {len(failures)} pointer(s) into the docs lead nowhere")
    sys.exit(1)
print("section_refs: every pointer into the docs leads to its section")
