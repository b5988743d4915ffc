#!/usr/bin/env python3
"""skinslide --help against README's Options table (README "Options"): the same options; each
number's default and range the same; an option of one method says so in both; and no help text
states one method's rule as everyone's (a word README ties to one method, as `lerp(` to the
paper's slide weights, names that method in the same help text).
Usage: SKINSLIDE=path/to/skinslide tests/cli/help_readme.py"""
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
# Words of one method: a help text that uses one names the method too.
METHOD_WORDS = {"lerp(": "paper", "square": "paper", " net": "paper", "chart": "elastic"}

binary = os.environ.get("SKINSLIDE")
if not binary or not os.access(binary, os.X_OK):
    print("help_readme.py: SKINSLIDE must name the skinslide program", file=sys.stderr)
    sys.exit(2)


def help_options():
    """{long name: (range or None, default or None, description)} from --help."""
    text = subprocess.run([binary, "--help"], capture_output=True, text=True, check=True).stdout
    options, current = {}, None
    for line in text.splitlines():
        head = re.match(r"^  (-\w,)?(--[\w-]+)", line)
        if head:
            # The description follows two spaces or more, or starts the next line.
            declared, _, description = re.split(r"(\s{2,})", line[2:] + "  ", maxsplit=1)
            rng = re.search(r"in \[([^ ]+) - ([^\]]+)\]", declared)
            default = re.search(r"=(\S+)", declared)
            current = head.group(2)
            options[current] = [rng.groups() if rng else None,
                                default.group(1) if default else None, description.strip()]
        elif current and line.startswith(" " * 36):
            options[current][2] = (options[current][2] + " " + line.strip()).strip()
        elif not line.strip():
            current = None
    return options


def readme_rows():
    """[(long names, default, range or None, meaning)] from README's Options table."""
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Options\n", 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in section.splitlines():
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        if len(cells) != 3 or not cells[0].startswith("`"):
            continue
        names = re.findall(r"--[\w-]+", cells[0])
        default = re.match(r"`([^`]*)`", cells[1])
        rng = re.search(r"\(([-\d.e+]+)\.\.([-\d.e+]+)\)", cells[1] + " " + cells[2])
        rows.append((names, default.group(1) if default else None,
                     rng.groups() if rng else None, cells[2]))
    return rows


failures = []
helps = help_options()
rows = readme_rows()
in_readme = {n for names, *_ in rows for n in names}
for name in sorted(set(helps) - in_readme):
    failures.append(f"{name}: in --help, not in README's Options table")
for name in sorted(in_readme - set(helps)):
    failures.append(f"{name}: in README's Options table, not in --help")

checked = 0
for names, default, rng, meaning in rows:
    if len(names) != 1 or names[0] not in helps:
        continue
    name = names[0]
    help_range, help_default, description = helps[name]
    if rng:
        checked += 1
        if not help_range or [float(x) for x in rng] != [float(x) for x in help_range]:
            failures.append(f"{name}: README's range {rng}, --help's {help_range}")
        try:
            if help_default is None or float(default) != float(help_default):
                failures.append(f"{name}: README's default {default}, --help's {help_default}")
        except ValueError:
            failures.append(f"{name}: README's default {default!r} is not a number")
    for method in ("elastic", "paper"):
        says_readme = meaning.lower().startswith(method) and "both methods" not in meaning
        both = "elastic:" in description.lower() and "paper:" in description.lower()
        says_help = description.lower().startswith(method) and not both
        if says_readme != says_help:
            failures.append(f"{name}: README {'gives' if says_readme else 'does not give'} it as "
                            f"{method} only; --help {'does' if says_help else 'does not'}")

for name, (_, _, description) in sorted(helps.items()):
    for word, method in METHOD_WORDS.items():
        if word in description and method not in description.lower():
            failures.append(f"{name}: its help uses {word.strip()!r}, a {method} method word, "
                            f"without naming the {method} method: {description!r}")

for f in failures:
    print("FAIL:", f, file=sys.stderr)
print(f"help_readme: {len(helps)} options in --help, {len(rows)} README rows, {checked} ranges "
      f"and defaults compared, {len(failures)} failed")
sys.exit(1 if failures else 0)
