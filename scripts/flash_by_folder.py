#!/usr/bin/env python3
"""Flash of a bare-metal image by source folder: where a renderer's bytes are.

Sums the sizes of the image's code and read-only symbols (nm -S -l: the line tables give each
symbol's file) by the project folder they come from (core/<stage>, firmware/<part>); symbols
without line information (tables GCC emits without a location, libgcc) are "unattributed".
RAM symbols (.bss, .data) are left out; so are the symbols whose name starts with one of the
--exclude prefixes (the scene's mesh and texture arrays). Aliases (two names at one address, as
GCC gives a class's complete and base constructors) are counted once. Prints a markdown table, largest
first, with each folder's three largest symbols.

  python3 scripts/flash_by_folder.py ELF [--exclude PREFIX ...] [--tool-prefix arm-none-eabi-]
"""

import argparse
import collections
import re
import subprocess
import sys

LINE = re.compile(r"^([0-9a-f]+) ([0-9a-f]+) (\w) (.*?)(?:\t(\S+):\d+)?$")
FOLDER = re.compile(r"/((?:core|firmware|hal)/[^/]+)/")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("elf")
    ap.add_argument("--exclude", action="append", default=[], metavar="PREFIX")
    ap.add_argument("--tool-prefix", default="arm-none-eabi-")
    args = ap.parse_args()
    try:
        out = subprocess.run([args.tool_prefix + "nm", "-S", "-l", "-C", args.elf],
                             capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"flash_by_folder: {args.elf}: {e}", file=sys.stderr)
        return 1
    sizes = collections.Counter()
    largest = collections.defaultdict(list)
    seen = set()
    for line in out.splitlines():
        m = LINE.match(line)
        if not m or m.group(3) in "bBdD" or (m.group(1), m.group(2)) in seen:
            continue
        seen.add((m.group(1), m.group(2)))
        size, name, path = int(m.group(2), 16), m.group(4), m.group(5) or ""
        if any(name.startswith(p) for p in args.exclude):
            continue
        f = FOLDER.search(path)
        folder = f.group(1) if f else ("libgcc" if "libgcc" in path else "unattributed")
        sizes[folder] += size
        short = re.sub(r"SpanSet\{[^}]*\}", "SpanSet{...}", name).split("(")[0]
        largest[folder].append((size, short or name))
    print("| folder | flash | largest symbols |")
    print("|---|---:|---|")
    for folder, size in sizes.most_common():
        top = sorted(largest[folder], reverse=True)[:3]
        names = ", ".join(f"`{n}` {s:,}" for s, n in top)
        print(f"| {folder} | {size:,} B | {names} |")
    print(f"| total | {sum(sizes.values()):,} B | |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
