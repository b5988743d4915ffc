#!/usr/bin/env python3
"""Every relative link of the repository's Markdown files resolves: README.md's Contents line and
the links between README.md and the READMEs beside the code (lib/*/README.md, tests/bench/*.md,
...). A link to a file names a file or folder of the clone; a `#anchor` (alone, or after a .md
file) names a heading of that file, as GitHub makes its anchors: lower case, punctuation but `-`
and `_` dropped, spaces to `-`, a repeated heading's anchor suffixed -1, -2, ... Links in code
blocks and spans are not links; http(s) and mailto links are not checked (no network).
Usage: tests/cli/readme_links.py"""
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LINK = re.compile(r"!?\[[^\]]*\]\(([^()\s]+)\)")


def markdown_files():
    """The Markdown files git tracks (or would: untracked, not ignored)."""
    out = subprocess.run(["git", "-C", str(ROOT), "ls-files", "--cached", "--others",
                          "--exclude-standard", "*.md"], capture_output=True, text=True)
    if out.returncode != 0:  # not a git clone: every .md file outside build trees
        return sorted(p for p in ROOT.rglob("*.md") if "build" not in p.relative_to(ROOT).parts[0])
    return sorted(ROOT / line for line in out.stdout.splitlines() if (ROOT / line).is_file())


def prose_lines(text, blank_spans=True):
    """(line number, line) outside fenced code blocks, code spans blanked unless not asked."""
    fence = None
    for n, line in enumerate(text.splitlines(), 1):
        stripped = line.lstrip()
        mark = re.match(r"(```+|~~~+)", stripped)
        if mark:
            if fence is None:
                fence = mark.group(1)[0] * 3
            elif stripped.startswith(fence):
                fence = None
            continue
        if fence is None:
            yield n, re.sub(r"`[^`]*`", "``", line) if blank_spans else line


def anchors(path, cache={}):
    if path not in cache:
        seen, found = {}, set()
        text = path.read_text(encoding="utf-8")
        for _, line in prose_lines(text, blank_spans=False):  # a heading's code spans count
            heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
            if not heading:
                continue
            title = heading.group(1)
            title = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", title)  # a link: its text
            slug = re.sub(r"[^\w\- ]", "", title.lower()).replace(" ", "-")
            n = seen.get(slug, 0)
            seen[slug] = n + 1
            found.add(slug if n == 0 else f"{slug}-{n}")
        cache[path] = found
    return cache[path]


failures, checked = [], 0
files = markdown_files()
for md in files:
    for n, line in prose_lines(md.read_text(encoding="utf-8")):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                continue
            checked += 1
            where = f"{md.relative_to(ROOT)}:{n}: {target}"
            name, _, anchor = target.partition("#")
            dest = (md.parent / name).resolve() if name else md
            if not dest.exists():
                failures.append(f"{where}: no file {dest.relative_to(ROOT) if dest.is_relative_to(ROOT) else dest}")
            elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
                failures.append(f"{where}: no heading with anchor #{anchor} in "
                                f"{dest.relative_to(ROOT)}")

for f in failures:
    print("FAIL:", f, file=sys.stderr)
print(f"readme_links: {checked} relative links in {len(files)} Markdown files, "
      f"{len(failures)} broken")
sys.exit(1 if failures else 0)
