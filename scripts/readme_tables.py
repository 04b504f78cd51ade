#!/usr/bin/env python3
"""Copies the per-method table of docs/accuracy.md (its methods with a median ratio within 2x) (written by erkn_accuracy_benchmark) into
README.md between its "BEGIN method table" and "END method table" markers: the README's
"Choosing a method" numbers come from that run, never typed. scripts/main.sh runs it after the
benchmark; with --check it only reports whether README.md is current (exit 1 if not)."""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
BEGIN = re.compile(r"<!-- BEGIN method table[^\n]*-->\n")
END = "<!-- END method table -->"


def method_table(accuracy):
    """The table under the '## One method for every problem' heading, with its caption."""
    section = accuracy.split("\n## One method for every problem", 1)
    if len(section) != 2:
        raise SystemExit("docs/accuracy.md has no 'One method for every problem' section")
    lines = section[1].split("\n")[1:]
    rows = [line for line in lines if line.startswith("|")]
    if len(rows) < 3:
        raise SystemExit("docs/accuracy.md's per-method table is empty")
    # the header, then the methods whose median ratio is within 2x (the rest: docs/accuracy.md)
    kept = [row for row in rows[2:] if within(row.split("|")[-2], 2.0)]
    return "\n".join(rows[:2] + kept) + "\n"


def within(cell, bound):
    try:
        return float(cell) <= bound
    except ValueError:  # "> 2"
        return False


def updated(readme, table):
    begin = BEGIN.search(readme)
    end = readme.find(END)
    if not begin or end < begin.end():
        raise SystemExit("README.md lacks the method table markers")
    return readme[:begin.end()] + table + readme[end:]


def main():
    readme_path = ROOT / "README.md"
    readme = readme_path.read_text()
    new = updated(readme, method_table((ROOT / "docs" / "accuracy.md").read_text()))
    if "--check" in sys.argv[1:]:
        if new != readme:
            print("README.md's method table differs from docs/accuracy.md", file=sys.stderr)
            return 1
        return 0
    readme_path.write_text(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
