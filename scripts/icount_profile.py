#!/usr/bin/env python3
"""Where the instructions of a benchmark frame go: runs lr_bench (firmware/bench) under QEMU with
the counting plugin in profile mode (scripts/icount.sh --profile) and attributes each measured
frame's instructions to functions, by the start address of every translated block that ran
between the frame's two markers (a block belongs to the function whose symbol precedes it).

usage: scripts/icount_profile.py [--top N] [--case NAME ...] --machine M ELF

Counts are exact per block; attributing a block to one function is exact too unless the block
falls through from one function into the next (GCC does not lay code out that way).
"""
import argparse
import bisect
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def functions(elf, prefix):
    """Sorted (address, demangled name) of the ELF's code symbols."""
    out = subprocess.run([prefix + "nm", "-n", "-C", "--defined-only", elf], check=True,
                         capture_output=True, text=True).stdout
    syms = []
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if len(parts) == 3 and parts[1] in "TtWw" and parts[2] and not parts[2].startswith("$"):
            syms.append((int(parts[0], 16) & ~1, parts[2]))
    return syms


def short(name, width=110):
    name = re.sub(r"\(.*\)( const)?$", "", name)  # no parameter lists
    return name if len(name) <= width else name[: width - 3] + "..."


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--machine", required=True)
    ap.add_argument("--top", type=int, default=15)
    ap.add_argument("--case", action="append", default=[])
    ap.add_argument("--tool-prefix", default="arm-none-eabi-")
    ap.add_argument("elf")
    args = ap.parse_args(argv)

    run = subprocess.run(["bash", os.path.join(ROOT, "scripts", "icount.sh"), "--profile",
                          "--machine", args.machine, args.elf, "lr_bench_marker"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.stderr.write(run.stdout + run.stderr)
        return 1
    syms = functions(args.elf, args.tool_prefix)
    starts = [a for a, _ in syms]

    markers, regions, cases = 0, [], []
    current = {}
    for line in run.stdout.splitlines():
        if line.startswith("icount: marker "):
            if markers > 0:
                regions.append(current)
            current = {}
            markers += 1
        elif line.startswith("icount: tb "):
            _, _, start, insns, execs = line.split()
            i = bisect.bisect_right(starts, int(start, 16)) - 1
            name = syms[i][1] if i >= 0 else start
            current[name] = current.get(name, 0) + int(insns) * int(execs)
        elif line.startswith("lr_bench: case "):
            cases.append(line.split()[2])
    regions.append(current)
    # The block lines after marker k+1 are region k (0-based): from marker k to marker k+1
    # (region 0 is from reset to the first marker). Case j is measured from marker 2j to 2j+1.
    for j, case in enumerate(cases):
        if args.case and case not in args.case:
            continue
        per_fn = regions[2 * j + 1]
        total = sum(per_fn.values())
        print(f"{case}: {total:,} instructions")
        for name, n in sorted(per_fn.items(), key=lambda kv: -kv[1])[: args.top]:
            print(f"  {n:>12,} {100.0 * n / total:5.1f} %  {short(name)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
