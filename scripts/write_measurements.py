#!/usr/bin/env python3
"""Writes a benchmark script's Markdown tables to docs/measurements/NAME.md (the scripts'
--write-docs mode), so that the figures in the docs are the last run's and never typed by hand.

Usage: scripts/write_measurements.py NAME COMMAND TITLE < TABLES.md

The file gets a title, a line saying which command wrote it, the tables from stdin, and the
"## Notes" section of the file it replaces, kept as it was: notes are written by hand (what the
figures mean), the tables only by the command.
"""
import os
import sys

NOTES = "## Notes"
USAGE = "usage: scripts/write_measurements.py NAME COMMAND TITLE < TABLES.md"


def main():
    if len(sys.argv) != 4:
        sys.exit(USAGE)
    name, command, title = sys.argv[1:4]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    path = os.path.join(root, "docs", "measurements", name + ".md")
    notes = ""
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            old = f.read()
        at = old.find("\n" + NOTES + "\n")
        if at >= 0:
            notes = old[at + 1:]
    tables = sys.stdin.read().strip()
    if not tables:
        sys.exit(f"write_measurements: no tables on stdin for {name}")
    text = (f"# {title}\n\n"
            f"Tables written by `{command}` (the notes below them by hand); run it again to "
            f"refresh them.\n\n{tables}\n")
    if notes:
        text += "\n" + notes.rstrip() + "\n"
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    print(f"write_measurements: wrote {os.path.relpath(path, root)}")


if __name__ == "__main__":
    main()
