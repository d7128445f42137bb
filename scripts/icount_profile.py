#!/usr/bin/env python3
"""Where the instructions of a measured region go: reads the profile the counting plugin wrote
(tools/qemu_icount, profile=PATH; scripts/icount.sh --profile OUT BEGIN END) and attributes each
instruction address's execution count to a function, a source file or a source folder.

usage: scripts/icount_profile.py ELF PROFILE [--by function|file|folder|stage[,...]] [--top N] [--tsv]
       scripts/icount_profile.py --machine M ELF [--case NAME ...] [--by ...] [--top N] [--tsv]

The first form reads PROFILE ("0xADDR COUNT" lines). The second runs firmware/bench's lr_bench
(any ELF whose measured frames lie between two calls of lr_bench_marker and which prints
"lr_bench: case NAME ..." after each) under scripts/icount.sh, once to find the cases and once per
selected case with that case's frame as the only profile period, and checks that the profile's sum
equals the frame's marker difference.

  --by function  the function (ELF symbol, arm-none-eabi-nm -S) whose code holds the address:
                 code inlined into a function counts as that function's
  --by file      the source file of the address's innermost location (arm-none-eabi-addr2line -i)
                 that is a file of this repository: inlined code counts where it is written, the
                 code of a standard-library header inlined into project code counts at the project
                 line it was inlined into
  --by folder    the same, grouped by folder: core/<stage>, firmware/<program>, hal/<backend>, ...
  --by stage     the renderer's stages (the rules: STAGE_RULES below): vertex, cull + bin, setup,
                 row loop + span entry, pixel loop, spans (textured and Phong), strip loop +
                 clears, other. Each address's inline chain is read from the innermost frame out;
                 the first file with a rule decides. The hand-allocated lanes visit
                 (core/span/lane_rows.hpp, one asm statement) is split by its disassembly: its
                 pixel loops (from each "ldrh r0, [r2, r6, lsl #1]" to the branch back to it, and
                 the rejected pixels' counter) are the pixel loop, the rest the row loop.
  In file and folder views, code with no project source location is a row of its own named after
  its symbol and library, from the linker map (ELF with .map next to it, or --map): "libgcc:
  __aeabi_ldivmod", "libc: memcpy"; "libstdc++: NAME" for a standard-library template emitted out
  of line; "other: NAME" otherwise (e.g. an ELF without line tables: build with CXXFLAGS=-g).

Counts are exact per instruction (the plugin's per-TB counts expanded to the TB's instructions);
the attribution is as exact as the ELF's symbol sizes and line tables (-g does not change code).
"""
import argparse
import bisect
import functools
import os
import re
import subprocess
import sys
import tempfile

SCRIPTS = os.path.dirname(os.path.realpath(__file__))
ROOT = os.path.dirname(SCRIPTS)  # --root changes it


def read_profile(path):
    """{address: count} from "0xADDR COUNT" lines."""
    counts = {}
    with open(path, encoding="ascii") as f:
        for number, line in enumerate(f, 1):
            parts = line.split()
            if len(parts) != 2 or not parts[0].startswith("0x"):
                raise SystemExit(f"icount_profile: {path}:{number}: expected '0xADDR COUNT'")
            address = int(parts[0], 16)
            counts[address] = counts.get(address, 0) + int(parts[1])
    return counts


class Symbols:
    """The ELF's code symbols (nm -S -C --defined-only), for address -> function."""

    def __init__(self, elf, prefix):
        out = subprocess.run([prefix + "nm", "-S", "-C", "--defined-only", elf], check=True,
                             capture_output=True, text=True).stdout
        by_start = {}
        for line in out.splitlines():
            # "ADDR SIZE TYPE NAME" or, without a size (assembly), "ADDR TYPE NAME".
            m = re.match(r"([0-9a-f]+) (?:([0-9a-f]+) )?([A-Za-z]) (.+)$", line)
            if not m or m.group(3) not in "TtWw" or m.group(4).startswith("$"):
                continue
            start = int(m.group(1), 16) & ~1
            size = int(m.group(2), 16) if m.group(2) else 0
            # Several names at one address (aliases): the sized one, else the first.
            if start not in by_start or (size and not by_start[start][1]):
                by_start[start] = (m.group(4), size)
        self.starts = sorted(by_start)
        self.entries = [by_start[s] for s in self.starts]

    def name(self, address):
        """The function holding address: the symbol at or before it whose size covers it; a
        symbol without a size (assembly) covers up to the next symbol."""
        i = bisect.bisect_right(self.starts, address) - 1
        if i < 0:
            return f"?? 0x{address:x}"
        name, size = self.entries[i]
        if size and address >= self.starts[i] + size:
            return f"?? 0x{address:x} (after {name})"
        return name


def read_map(path):
    """Sorted (start, end, library) of the code input sections that come from an archive outside
    the repository (the toolchain's libgcc.a, libc_nano.a, ...), from a GNU ld map file."""
    ranges = []
    if not path or not os.path.isfile(path):
        return ranges
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    # Only the memory map: the "Discarded input sections" before it list sections at address 0.
    _, found, text = text.partition("\nLinker script and memory map\n")
    lines = text.splitlines() if found else []
    section = None
    for line in lines:
        # " .text.name  0xADDR 0xSIZE FILE" or " .text.name" then "  0xADDR 0xSIZE FILE".
        m = re.match(r"^ (\.text\S*)(?:\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+(\S.*))?$", line)
        if m:
            section = m.group(1)
            if m.group(2) is None:
                continue
            start, size, origin = int(m.group(2), 16), int(m.group(3), 16), m.group(4)
        else:
            m = re.match(r"^\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+(\S.*)$", line)
            if not (m and section):
                section = None
                continue
            start, size, origin = int(m.group(1), 16), int(m.group(2), 16), m.group(3)
        section = None
        a = re.match(r"^(.*?([^/]+)\.a)\((.*)\)$", origin.strip())
        if not a or size == 0:
            continue
        archive = os.path.normpath(a.group(1))
        if not os.path.isabs(archive) or archive.startswith(ROOT + os.sep):
            continue  # a project library (core/liblr_core.a, relative to the build tree)
        lib = re.sub(r"_nano$", "", a.group(2))  # libc_nano -> libc
        ranges.append((start, start + size, lib))
    ranges.sort()
    return ranges


def library_of(ranges, starts, address):
    i = bisect.bisect_right(starts, address) - 1
    if i >= 0 and ranges[i][0] <= address < ranges[i][1]:
        return ranges[i][2]
    return None


def locations(elf, prefix, addresses):
    """{address: [(function, file, line), ...]}: each address's inlining chain, innermost first
    (one arm-none-eabi-addr2line -a -f -C -i process for all addresses)."""
    if not addresses:
        return {}
    # Each address is asked as address + 1, a byte of the same instruction (Thumb instructions
    # have 2 or 4 bytes): GNU addr2line 2.40, reading many addresses, answers "??" for an address
    # equal to the end of the line sequence it used for the address before (the first instruction
    # of the next function, with -ffunction-sections), as if the end were inside the sequence.
    text = "".join(f"0x{a + 1:x}\n" for a in addresses)
    out = subprocess.run([prefix + "addr2line", "-e", elf, "-a", "-f", "-C", "-i"], input=text,
                         check=True, capture_output=True, text=True).stdout.splitlines()
    chains, current, i = {}, None, 0
    while i < len(out):
        line = out[i]
        if re.fullmatch(r"0x[0-9a-f]+", line):
            current = int(line, 16) - 1
            chains[current] = []
            i += 1
            continue
        function = line
        where = out[i + 1] if i + 1 < len(out) else "??:0"
        i += 2
        where = re.sub(r" \(discriminator \d+\)$", "", where)
        file, _, number = where.rpartition(":")
        chains[current].append((function, file, number))
    return chains


@functools.lru_cache(maxsize=None)
def project_path(file):
    """The path relative to the repository when file is one of its sources, else None."""
    if not file or file.startswith("??"):
        return None
    if not os.path.isabs(file):
        # A bare compilation-unit name (an ELF without line tables: "main.cpp:?") says no folder.
        if not os.path.exists(os.path.join(ROOT, file)):
            return None
        file = os.path.join(ROOT, file)
    path = os.path.realpath(file)
    if not path.startswith(ROOT + os.sep):
        return None
    rel = os.path.relpath(path, ROOT)
    # Generated sources in a build tree (build/<preset>/...): the path inside that tree.
    parts = rel.split(os.sep)
    if parts[0].startswith("build") and len(parts) > 2:
        rel = os.path.join("(generated)", *parts[2:])
    return rel


def folder_of(rel):
    """core/span/x.cpp -> core/span; firmware/bench/main.cpp -> firmware/bench; a.cpp -> ."""
    parts = rel.split(os.sep)[:-1]
    return os.sep.join(parts[:2]) if parts else "."


def short(name, full):
    if full:
        return name
    return re.sub(r"\((?:[^()]|\([^()]*\))*\)( const)?( \[clone [^\]]*\])*$", "", name)


# The stage of a source file (relative path; first match wins); None: no rule (the next frame
# out of the inline chain decides). setup.StripLoop::activate sets triangles up (set_up is
# inlined there): its strip_loop.hpp lines are setup.
STAGE_RULES = [
    (r"core/(vertex|lighting)/", "vertex"),
    (r"core/binning/", "cull + bin"),
    (r"core/setup/row_edge\.hpp$", "row loop + span entry"),
    (r"core/setup/(active_triangle|strip_rows)\.hpp$", None),
    (r"core/setup/", "setup"),
    (r"core/span/(lane_span|untextured_span)\.hpp$", "pixel loop"),
    (r"core/span/lane_rows\.hpp$", "row loop + span entry"),
    (r"core/raster/(untextured_rows|row_loop|legacy_rows)\.hpp$", "row loop + span entry"),
    (r"core/(span|texture)/", "spans (textured, Phong)"),
    (r"core/(raster|output)/|firmware/common/", "strip loop + clears"),
]
STAGES = ["vertex", "cull + bin", "setup", "row loop + span entry", "pixel loop",
          "spans (textured, Phong)", "strip loop + clears", "other"]


def lane_pixel_addresses(elf, prefix):
    """The pixel loops of the hand-allocated lanes visit (core/span/lane_rows.hpp): from each
    "ldrh r0, [r2, r6, lsl #1]" to the branch back to it, and the 4 instructions at the target of
    that loop's "bls" (the rejected pixels' counter)."""
    out = subprocess.run([prefix + "objdump", "-d", "--no-show-raw-insn", elf], check=True,
                         capture_output=True, text=True).stdout
    insns = []
    for line in out.splitlines():
        m = re.match(r"^\s+([0-9a-f]+):\s+(\S+)\s*(.*)$", line)
        if m:
            insns.append((int(m.group(1), 16), m.group(2), m.group(3)))
    index = {a: i for i, (a, _, _) in enumerate(insns)}
    pixels = set()
    for i, (a, op, args) in enumerate(insns):
        if not (op.startswith("ldrh") and re.match(r"r0, \[r2, r6, lsl #1\]", args)):
            continue
        for j in range(i, min(i + 24, len(insns))):
            bj, opj, argsj = insns[j]
            target = re.match(r"([0-9a-f]+)", argsj)
            if opj.startswith("bls") and target and int(target.group(1), 16) in index:
                k = index[int(target.group(1), 16)]
                pixels.update(x[0] for x in insns[k:k + 4])
            if opj.startswith("bne") and target and int(target.group(1), 16) == a:
                pixels.update(x[0] for x in insns[i:j + 1])
                break
    return pixels


def stage_of_chain(chain, function, address, lane_pixels):
    for _, f, _ in chain:
        rel = project_path(f)
        if rel is None:
            continue
        if rel.endswith("core/raster/strip_loop.hpp") and "::activate(" in function:
            return "setup"
        for pattern, stage in STAGE_RULES:
            if re.search(pattern, rel):
                if stage is None:
                    break
                if stage == "row loop + span entry" and rel.endswith("lane_rows.hpp") and \
                        address in lane_pixels:
                    return "pixel loop"
                return stage
    return None


def attribute(elf, counts, by, prefix, map_path, full_names):
    """{row name: instructions}."""
    symbols = Symbols(elf, prefix)
    rows = {}
    if by == "function":
        for address, n in counts.items():
            key = short(symbols.name(address), full_names)
            rows[key] = rows.get(key, 0) + n
        return rows, 0
    ranges = read_map(map_path)
    starts = [r[0] for r in ranges]
    chains = locations(elf, prefix, sorted(counts))
    without_lines = 0
    if by == "stage":
        lane_pixels = lane_pixel_addresses(elf, prefix)
        full = Symbols(elf, prefix)
        rows = dict.fromkeys(STAGES, 0)
        for address, n in counts.items():
            chain = chains.get(address, [])
            if not any(project_path(f) for _, f, _ in chain):
                without_lines += n
            stage = stage_of_chain(chain, full.name(address), address, lane_pixels)
            if stage is None:
                lib = library_of(ranges, starts, address)
                name = short(symbols.name(address), False)
                stage = "strip loop + clears" if lib == "libc" and re.match(
                    r"mem(set|cpy|move)$", name) else "other"
            rows[stage] += n
        return rows, without_lines
    for address, n in counts.items():
        chain = chains.get(address, [])
        rel = next((p for p in (project_path(f) for _, f, _ in chain) if p), None)
        if rel is not None:
            key = rel if by == "file" else folder_of(rel)
        else:
            name = short(symbols.name(address), full_names)
            lib = library_of(ranges, starts, address)
            if lib is None:
                lib = "libstdc++" if any("/c++/" in f for _, f, _ in chain) else "other"
            if lib == "other":
                without_lines += n
            key = f"{lib}: {name}"
        rows[key] = rows.get(key, 0) + n
    return rows, without_lines


def print_table(title, rows, by, top, tsv, width_limit, out=sys.stdout):
    total = sum(rows.values())
    ordered = sorted(rows.items(), key=lambda kv: (-kv[1], kv[0]))
    if top and len(ordered) > top:
        rest = ordered[top:]
        ordered = ordered[:top] + [(f"({len(rest)} more rows)", sum(n for _, n in rest))]
    if tsv:
        for name, n in ordered:
            out.write(f"{name}\t{n}\t{100.0 * n / total if total else 0.0:.2f}\n")
        return
    out.write(f"{title}: {total:,} instructions, by {by}\n")
    width = max([len(f"{total:,}"), len("instructions")])
    out.write(f"  {'instructions':>{width}}       %  {by}\n")
    for name, n in ordered:
        if width_limit and len(name) > width_limit:
            name = name[: width_limit - 3] + "..."  # display only: the rows were keyed in full
        out.write(f"  {n:>{width},} {100.0 * n / total if total else 0.0:7.2f}  {name}\n")


def run_icount(args, extra):
    cmd = ["bash", os.path.join(SCRIPTS, "icount.sh")]
    if args.plugin:
        cmd += ["--plugin", args.plugin]
    cmd += extra + ["--machine", args.machine, args.elf, "lr_bench_marker"]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.stderr.write(run.stdout + run.stderr)
        raise SystemExit(1)
    return run.stdout


def bench_cases(output):
    """[(case name, marker difference)] from an lr_bench run's output: case j is measured from
    marker line 2j to 2j+1 (main.cpp calls lr_bench_marker before and after each frame)."""
    marks = [int(m) for m in re.findall(r"^icount: marker \S+ lr_bench_marker at (\d+)$", output,
                                         re.M)]
    names = re.findall(r"^lr_bench: case (\S+) ", output, re.M)
    if len(marks) != 2 * len(names):
        raise SystemExit(f"icount_profile: {len(marks)} marker lines for {len(names)} cases")
    return [(name, marks[2 * j + 1] - marks[2 * j]) for j, name in enumerate(names)]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n".join(__doc__.splitlines()[3:]))
    ap.add_argument("elf")
    ap.add_argument("profile", nargs="?")
    ap.add_argument("--by", default=None, help="function, file, folder or stage; several "
                    "separated by commas print one table each")
    ap.add_argument("--top", type=int, default=0, help="rows to print (0: all; default 0)")
    ap.add_argument("--tsv", action="store_true", help="NAME<TAB>INSTRUCTIONS<TAB>PERCENT lines")
    ap.add_argument("--full-names", action="store_true", help="keep parameter lists, clone suffixes, long names")
    ap.add_argument("--map", help="linker map (default: ELF's name with .map, if it exists)")
    ap.add_argument("--tool-prefix", default="arm-none-eabi-")
    ap.add_argument("--root", help="the source tree whose files are project files (default: this "
                    "script's repository)")
    ap.add_argument("--machine", help="run lr_bench under QEMU (second form)")
    ap.add_argument("--case", action="append", default=[], help="lr_bench case (repeatable)")
    ap.add_argument("--plugin", help="passed to scripts/icount.sh")
    args = ap.parse_args(argv)
    global ROOT
    if args.root:
        ROOT = os.path.realpath(args.root)
    map_path = args.map or os.path.splitext(args.elf)[0] + ".map"

    views = (args.by or "function").split(",")
    for by in views:
        if by not in ("function", "file", "folder", "stage"):
            ap.error(f"--by {by}: function, file, folder or stage")
    if args.profile is not None:
        if args.machine or args.case:
            ap.error("--machine/--case run lr_bench: give no PROFILE with them")
        counts = read_profile(args.profile)
        for by in views:
            rows, no_lines = attribute(args.elf, counts, by, args.tool_prefix, map_path,
                                       args.full_names)
            print_table(args.profile, rows, by, args.top, args.tsv, 0 if args.full_names else 100)
            warn_no_lines(no_lines, rows, by)
        return 0

    if not args.machine:
        ap.error("give PROFILE, or --machine to run lr_bench")
    cases = bench_cases(run_icount(args, []))
    unknown = set(args.case) - {name for name, _ in cases}
    if unknown:
        raise SystemExit(f"icount_profile: no case {', '.join(sorted(unknown))} in {args.elf}")
    with tempfile.TemporaryDirectory() as tmp:
        for j, (name, difference) in enumerate(cases):
            if args.case and name not in args.case:
                continue
            path = os.path.join(tmp, f"{name}.profile")
            # Begin and end are the same marker: the plugin's periods are the frames, in order.
            run_icount(args, ["--profile", path, "lr_bench_marker", "lr_bench_marker",
                              "--profile-skip", str(j), "--profile-count", "1"])
            counts = read_profile(path)
            if sum(counts.values()) != difference:
                raise SystemExit(f"icount_profile: case {name}: the profile sums to "
                                 f"{sum(counts.values())}, the markers differ by {difference}")
            for by in views:
                rows, no_lines = attribute(args.elf, counts, by, args.tool_prefix, map_path,
                                           args.full_names)
                print_table(f"{name} (= its marker difference)", rows, by, args.top, args.tsv,
                            0 if args.full_names else 100)
                warn_no_lines(no_lines, rows, by)
    return 0


def warn_no_lines(no_lines, rows, by):
    total = sum(rows.values())
    if by != "function" and total and no_lines * 2 > total:
        sys.stderr.write("icount_profile: most instructions have no source line: the ELF has no "
                         "line tables (configure the cross build with CXXFLAGS=-g)\n")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
