#!/usr/bin/env python3
"""skinslide --help against README's Options table (README "Options"): the same options in the
same groups, in the same order of groups; each number's default and range the same; an option of
one method says so in both; and no help text states one method's rule as everyone's (a word
README ties to one method, as `lerp(` to the paper's slide weights, names that method in the same
help text). And the help of skinslide, `skinslide compare` and `skinslide join` reads in 100
columns, with no CLI11 type marker (`FILE:FILE`, `N:INT in [0 - 100]=0`, `Excludes:`).
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


HELP_COLUMNS = 100
TEXT_COLUMN = 30  # where an option's text starts (cli/help_format.cpp kTextColumn)
# What CLI11's own formatter writes and ours never does: a type with its checks joined by ':'
# (FILE:FILE, INT:INT in [0 - 100], TEXT:{a,b}), a default after '=', CLI11's words.
RAW_MARKERS = [r"\b[A-Z]+:[A-Z{]", r"\bin \[[-\d.e+]+ - ", r"^\s+-\S.*\S=\S", r"\bExcludes:", r"\bNeeds:",
               r"\bREQUIRED\b", r"\b(TEXT|INT|UINT|FLOAT)\b", r"^POSITIONALS:", r"^OPTIONS:"]


def help_text(*command):
    return subprocess.run([binary, *command, "--help"], capture_output=True, text=True,
                          check=True).stdout


def help_options(text):
    """({name: (range or None, default or None, description)}, [(group, [names])]) from --help:
    long names, and positional ones (BIND)."""
    options, groups, current = {}, [], None
    listing = False  # past the description: in the groups of options
    for line in text.splitlines():
        listing = listing or line.startswith("Usage:")
        group = listing and re.match(r"^(\w[\w ]*):$", line)
        head = re.match(r"^  (-\w, )?(--[\w-]+|[A-Z][A-Z.]*)( |$)", line)
        if group:
            groups.append((group.group(1), []))
        elif head:
            current = head.group(2)
            # The text starts beside a short name and argument, else on the next line.
            beside = line[:TEXT_COLUMN].endswith(" ")
            options[current] = [None, None, line[TEXT_COLUMN:].strip() if beside else ""]
            if groups:
                groups[-1][1].append(current)
        elif current and line.startswith(" " * TEXT_COLUMN):
            options[current][2] = (options[current][2] + " " + line.strip()).strip()
        elif not line.strip():
            current = None
    for option in options.values():
        # The notes after the text: "(default 3; 1..1000; not with --x)".
        notes = re.search(r"\(([^()]*)\)$", option[2])
        if notes:
            rng = re.search(r"(?:^|; )([-\d.e+]+)\.\.([-\d.e+]+)(?:;|$)", notes.group(1))
            default = re.search(r"(?:^|; )default ([^;]+)", notes.group(1))
            option[0] = rng.groups() if rng else None
            option[1] = default.group(1) if default else None
    return options, groups


def readme_rows():
    """([(names, default, range or None, meaning)], [(group, [names])]) from README's Options
    table: long names and positional ones (`BIND`)."""
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Options\n", 1)[1].split("\n## ", 1)[0]
    rows, groups = [], []
    for line in section.splitlines():
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        group = re.match(r"^\*\*(.+)\*\*$", cells[0]) if cells else None
        if group:
            groups.append((group.group(1), []))
        if len(cells) != 3 or not cells[0].startswith("`"):
            continue
        names = re.findall(r"--[\w-]+", cells[0]) or re.findall(r"^`([A-Z][A-Z.]*)`", cells[0])
        if groups:
            groups[-1][1].extend(names)
        default = re.match(r"`([^`]*)`", cells[1])
        rng = re.search(r"\(([-\d.e+]+)\.\.([-\d.e+]+)\)", cells[1] + " " + cells[2])
        rows.append((names, default.group(1) if default else None,
                     rng.groups() if rng else None, cells[2]))
    return rows, groups


failures = []
main_help = help_text()
helps, help_groups = help_options(main_help)
rows, readme_groups = readme_rows()
in_readme = {n for names, *_ in rows for n in names}
for name in sorted(set(helps) - in_readme):
    failures.append(f"{name}: in --help, not in README's Options table")
for name in sorted(in_readme - set(helps)):
    failures.append(f"{name}: in README's Options table, not in --help")
shown = [(g, [n for n in names if n in in_readme]) for g, names in help_groups]
tabled = [(g, [n for n in names if n in helps]) for g, names in readme_groups]
if [g for g, _ in shown] != [g for g, _ in tabled]:
    failures.append(f"--help's groups {[g for g, _ in shown]}, README's {[g for g, _ in tabled]}")
for (group, names), (_, table_names) in zip(shown, tabled):
    if sorted(names) != sorted(table_names):
        failures.append(f"group {group}: --help has {names}, README {table_names}")

lines = 0
for command in ((), ("compare",), ("join",)):
    text = main_help if not command else help_text(*command)
    what = " ".join(("skinslide",) + command) + " --help"
    for n, line in enumerate(text.splitlines(), 1):
        lines += 1
        if len(line) > HELP_COLUMNS:
            failures.append(f"{what}: line {n} is {len(line)} columns (at most {HELP_COLUMNS}): "
                            f"{line!r}")
        for marker in RAW_MARKERS:
            if re.search(marker, line):
                failures.append(f"{what}: line {n} holds a CLI11 marker ({marker}): {line!r}")

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
print(f"help_readme: {len(helps)} options in --help in {len(help_groups)} groups, {len(rows)} "
      f"README rows, {checked} ranges and defaults compared, {lines} help lines read, "
      f"{len(failures)} failed")
sys.exit(1 if failures else 0)
