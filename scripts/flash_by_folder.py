#!/usr/bin/env python3
"""Flash of a bare-metal image by source folder: where a renderer's bytes are.

Sums the sizes of the image's code and read-only symbols (nm -S -l: the line tables give each
symbol's file) by the project folder they come from (core/<stage>, firmware/<part>); symbols
without line information (tables GCC emits without a location, libgcc) are "unattributed".
Assembly functions without a size (libgcc's __aeabi_ldivmod) count up to the next symbol.
RAM symbols (.bss, .data) are left out; so are the symbols whose name starts with one of the
--exclude prefixes (the scene's mesh and texture arrays). Aliases (two names at one address, as
GCC gives a class's complete and base constructors) are counted once. Prints a markdown table, largest
first, with each folder's three largest symbols.

--renderer prints instead the renderer's own bytes and what the program owns (one line each,
"renderer BYTES" and "program BYTES NAMES..."). The image's references (the relocations that
--emit-relocs keeps: calls, literal pools, tables of pointers) are followed from the program's
code (firmware/*) into the renderer's entries: the core/ and hal/ symbols it references, but
for the functions named by --program-api (the project's API the program calls for itself, its
camera and model matrix: they and what only they reach are the program's). The renderer is
everything reached from its entries: core/, hal/, and the libgcc helpers and unattributed
tables they use, never a firmware/ symbol (the program's sink, startup and C library shims); an
API function is the renderer's only when the renderer reaches it. A core/ or hal/ symbol that
nothing references counts as the renderer's; renderer code inlined into a program function
(Renderer::render() into main at -O3) counts as the program's.

  python3 scripts/flash_by_folder.py ELF [--exclude PREFIX ...] [--tool-prefix arm-none-eabi-]
                                         [--renderer [--program-api NAME ...]]
"""

import argparse
import bisect
import collections
import re
import subprocess
import sys

LINE = re.compile(r"^([0-9a-f]+) ([0-9a-f]+) (\w) (.*?)(?:\t(\S+):\d+)?$")
SIZELESS = re.compile(r"^([0-9a-f]+) ([TtWw]) (.*?)(?:\t(\S+):\d+)?$")
FOLDER = re.compile(r"/((?:core|firmware|hal)/[^/]+)/")
RELOC = re.compile(r"^([0-9a-f]{8})\s+[0-9a-f]{8}\s+(R_ARM_\w+)\s+([0-9a-f]{8})\s+(\S+)")
SECTION = re.compile(r"^\s*\d+\s+(\S+)\s+([0-9a-f]+)\s+([0-9a-f]+)\s+[0-9a-f]+\s+([0-9a-f]+)")


def run(tool, *args):
    return subprocess.run([tool, *args], capture_output=True, text=True, check=True).stdout


class Symbol:
    def __init__(self, addr, size, name, folder):
        self.addr, self.size, self.name, self.folder = addr, size, name, folder


def read_symbols(elf, tool_prefix):
    """Flash symbols (aliases once), sorted by address; sizeless code up to the next symbol."""
    out = run(tool_prefix + "nm", "-S", "-l", "-C", elf)
    found, sizeless, starts = {}, [], set()
    for line in out.splitlines():
        m = LINE.match(line)
        if m:
            if m.group(3) in "bBdD":
                continue
            addr, size = int(m.group(1), 16), int(m.group(2), 16)
            name, path = m.group(4), m.group(5) or ""
            starts.add(addr)
        else:
            m = SIZELESS.match(line)
            if not m:
                continue
            addr, size, name, path = int(m.group(1), 16), None, m.group(3), m.group(4) or ""
            starts.add(addr)
        f = FOLDER.search(path)
        folder = f.group(1) if f else ("libgcc" if "libgcc" in path else "unattributed")
        if size is None:
            sizeless.append((addr, name, folder))
        elif size and (addr, size) not in found:
            found[(addr, size)] = Symbol(addr, size, name, folder)
    covered = {a for a, _ in found}
    ordered = sorted(starts)
    for addr, name, folder in sizeless:
        i = bisect.bisect_right(ordered, addr)
        if addr in covered or i == len(ordered):
            continue
        found[(addr, 0)] = Symbol(addr, ordered[i] - addr, name, folder)
        covered.add(addr)
    return sorted(found.values(), key=lambda s: s.addr)


def references(elf, tool_prefix, symbols):
    """Edges (from symbol, to symbol) of the image's relocations in its loaded sections."""
    sections = []  # (vma, size, file offset) of the loaded sections, for the words ABS32 wrote
    for m in map(SECTION.match, run(tool_prefix + "objdump", "-h", elf).splitlines()):
        if m:
            sections.append((int(m.group(3), 16), int(m.group(2), 16), int(m.group(4), 16)))
    with open(elf, "rb") as f:
        image = f.read()
    starts = [s.addr for s in symbols]

    def containing(addr):
        i = bisect.bisect_right(starts, addr) - 1
        return symbols[i] if i >= 0 and addr < symbols[i].addr + symbols[i].size else None

    def word_at(addr):
        for vma, size, off in sections:
            if vma <= addr < vma + size:
                return int.from_bytes(image[off + addr - vma:off + addr - vma + 4], "little")
        return None

    edges = collections.defaultdict(set)
    section = None
    for line in run(tool_prefix + "readelf", "-rW", elf).splitlines():
        if line.startswith("Relocation section"):
            section = line.split("'")[1]
            continue
        m = RELOC.match(line)
        if not m or section.startswith(".rel.debug") or section == ".rel.comment":
            continue
        source = containing(int(m.group(1), 16))
        kind = m.group(2)
        if kind in ("R_ARM_ABS32", "R_ARM_TARGET1"):
            value = word_at(int(m.group(1), 16))  # S + A, as the linker wrote it
        elif m.group(4).startswith("."):
            continue  # a branch to a section symbol: none in the images (GCC names its targets)
        else:
            value = int(m.group(3), 16)
        target = containing(value) if value is not None else None
        if source and target and target is not source:
            edges[id(source)].add(target)
    return edges


def renderer_split(elf, tool_prefix, excluded, program_api):
    symbols = [s for s in read_symbols(elf, tool_prefix)
               if not any(s.name.startswith(p) for p in excluded)]
    edges = references(elf, tool_prefix, symbols)

    def is_api(s):
        return any(s.name.startswith(n) for n in program_api)

    def walk(roots, enter):
        seen, todo = {id(s) for s in roots}, list(roots)
        while todo:
            for t in edges.get(id(todo.pop()), ()):
                if id(t) not in seen and enter(t):
                    seen.add(id(t))
                    todo.append(t)
        return seen

    # The renderer's entries: what the program's own code (firmware/) references in core/ and
    # hal/, but for the API functions it calls for itself (they and what they call are its).
    entries = [t for s in symbols if s.folder.startswith("firmware/") for t in edges.get(id(s), ())
               if t.folder.startswith(("core/", "hal/")) and not is_api(t)]
    renderer = walk(entries, lambda t: not t.folder.startswith("firmware/"))
    referenced = {id(t) for targets in edges.values() for t in targets}
    for s in symbols:  # referenced by nobody: the renderer's if it is core's or hal's
        if s.folder.startswith(("core/", "hal/")) and not is_api(s) and id(s) not in referenced:
            renderer.add(id(s))
    mine = [s for s in symbols if id(s) in renderer]
    theirs = [s for s in symbols if id(s) not in renderer]
    return mine, theirs


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("elf")
    ap.add_argument("--exclude", action="append", default=[], metavar="PREFIX")
    ap.add_argument("--tool-prefix", default="arm-none-eabi-")
    ap.add_argument("--renderer", action="store_true",
                    help="print the renderer's bytes and the program's (see above)")
    ap.add_argument("--program-api", action="append", default=[], metavar="NAME",
                    help="a core function the program calls for itself (a name's start)")
    args = ap.parse_args()
    try:
        if args.renderer:
            mine, theirs = renderer_split(args.elf, args.tool_prefix, args.exclude,
                                          args.program_api)
            print(f"renderer {sum(s.size for s in mine)}")
            # The project's symbols among them (not the program's own, nor compiler tables).
            core = sorted({re.sub(r"(?<=\w)\(.*", "", s.name) for s in theirs
                           if not s.folder.startswith("firmware/") and
                           s.name.startswith("lr::") and not s.name.startswith("lr::fw::")})
            print(f"program {sum(s.size for s in theirs)} " + "; ".join(core))
            return 0
        symbols = read_symbols(args.elf, args.tool_prefix)
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"flash_by_folder: {args.elf}: {e}", file=sys.stderr)
        return 1
    sizes = collections.Counter()
    largest = collections.defaultdict(list)
    for s in symbols:
        if any(s.name.startswith(p) for p in args.exclude):
            continue
        sizes[s.folder] += s.size
        short = re.sub(r"SpanSet\{[^}]*\}", "SpanSet{...}", s.name).split("(")[0]
        largest[s.folder].append((s.size, short or s.name))
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
