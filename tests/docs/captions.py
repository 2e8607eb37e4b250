#!/usr/bin/env python3
"""The captions of the screenshots name the levels the pictures show.

scripts/screenshots.sh names each picture after the level it shows: docs/screenshots/<stem>.png
or <stem>-<view>.png for levels/<stem>.json. In README.md and docs/*.md, a picture of a level
written `![alt](.../screenshots/<stem>.png) caption` must have the level file's "name" as its
alt text and start its caption, if any, with it (after a playlist number "N. ", which must be the level's
place in levels/playlist.txt); a caption may not name another level. Fails naming the file,
line and caption.
Usage: python3 tests/docs/captions.py [project root]   (ctest: docs.captions)
"""
import json
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
me = "tests/docs/captions.py"

titles = {path.stem: json.loads(path.read_text())["name"] for path in (root / "levels").glob("*.json")}
playlist = []
for line in (root / "levels/playlist.txt").read_text().splitlines():
    stem = line.split("#", 1)[0].strip()
    if stem:
        playlist.append(stem)

picture = re.compile(r"!\[([^\]]*)\]\(([^)]*screenshots/([A-Za-z0-9_.-]+)\.png)\)([^|!]*)")
failures = []
pictures = 0
for page in [root / "README.md"] + sorted((root / "docs").rglob("*.md")):
    for number, line in enumerate(page.read_text().splitlines(), 1):
        for alt, path, name, caption in picture.findall(line):
            where = f"{page.relative_to(root)}:{number}"
            pictures += 1
            caption = caption.strip()
            stem = name if name in titles else name.split("-", 1)[0]
            if stem not in titles:
                continue  # not a level's picture
            title = titles[stem]
            if not (page.parent / path).is_file():
                failures.append(f"{where}: {path}: no such picture")
            others = [t for s, t in titles.items() if s != stem and t in caption + " " + alt
                      and t not in title]
            if others:
                failures.append(f"{where}: the picture of levels/{stem}.json (\"{title}\") is captioned "
                                f"\"{caption}\", which names the level \"{others[0]}\"")
            if name != stem:
                continue  # a view of the level (pressure, particles): its caption may say so
            if alt != title:
                failures.append(f"{where}: the picture of levels/{stem}.json has the alt text \"{alt}\"; "
                                f"the level's name is \"{title}\"")
            match = re.match(r"(\d+)\.\s+(.*)", caption)
            text = match.group(2) if match else caption
            if text and not text.startswith(title):
                failures.append(f"{where}: the picture of levels/{stem}.json is captioned \"{caption}\"; "
                                f"the caption should start with the level's name \"{title}\"")
            if match:
                place = playlist.index(stem) + 1 if stem in playlist else None
                if place != int(match.group(1)):
                    failures.append(f"{where}: the caption \"{caption}\" numbers levels/{stem}.json "
                                    f"{match.group(1)}; it is number {place} of levels/playlist.txt")

for failure in failures:
    print(f"{me}: {failure}", file=sys.stderr)
if failures:
    sys.exit(f"{me}: {len(failures)} caption(s) do not name the level their picture shows")
print(f"{me}: the captions of {pictures} pictures name the levels they show")
