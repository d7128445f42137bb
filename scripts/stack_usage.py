#!/usr/bin/env python3
"""Worst-case stack depth of a bare-metal image's entry points.

    stack_usage.py ELF BUILD_DIR [--entry Reset_Handler --entry main]
                   [--handler HardFault_Handler ...] [--vector-table .isr_vector]
                   [--indirect REGEX ...] [--indirect-from CALLER_REGEX TARGET_REGEX ...]
                   [--verbose] [--machine]

Prints, per entry, the deepest stack its calls can reach and the call path that reaches it
("(*)" marks a call through a pointer):

    main: 3,904 B via main -> (anonymous namespace)::render_frame -> lr::FrontEnd::draw -> ...

and exits 1, naming the function, when no sound bound exists: recursion, an unbounded
(dynamic) frame, an unknown function, an unresolved indirect call. Python's standard library
only; arm-none-eabi-objdump and -c++filt are run as tools.

Method
------
Functions are the ELF's defined function symbols (STT_FUNC, read from .symtab: nm cannot tell
code from the .rodata that the linker script puts into .text). A function the linker dropped
(--gc-sections) is not in the ELF and is ignored, wherever it appears.

Frames and calls come from GCC's call-graph files (-fcallgraph-info=su: <object>.ci next to each
object). Only the .ci files of the image's own objects are read: those the map file (ELF with
.map, or --map) names, found under BUILD_DIR (<object minus extension>.ci; archive members by
name under the archive's directory). Without a map file every .ci under BUILD_DIR is read,
which is only safe when no two images' objects define the same function differently. Local
functions are matched to their translation unit through the ELF's FILE symbols. A node's label
holds "N bytes (static|dynamic|dynamic,bounded)": static and dynamic,bounded give N (GCC: an
upper bound); dynamic (unbounded) is an error. A function in several objects (template
instances, inline functions) takes the largest frame and the union of their calls.

The disassembly (objdump -d) adds what the .ci files cannot see (inline assembly, libgcc):
  - calls: bl to an address (a function's start, or its middle: the function containing it),
    and branches (b, b<cond>, .n/.w) leaving the function: tail calls, which cost the callee's
    depth but not the caller's frame, whose epilogue ran before the branch (a .ci edge that the
    code only branches to is such a sibling call; a branch into a ".cold" part, whose caller's
    frame is still live, counts as a call). `ldr rN, [pc, #..]` right before `bx rN`/`blx rN`
    is a direct branch to the literal (the long-branch idiom of a naked HardFault_Handler);
  - indirect calls: blx rN; bx rN unless rN was restored from the stack in the function (pop
    {.., r3}; bx r3 is libgcc's return); ldr pc / mov pc, rN unless they dispatch a switch:
    a table of addresses inside the same function (words of the image pointing into it);
  - frames of functions without a .ci node (libgcc: __aeabi_ldivmod, __udivmoddi4, __divsi3,
    __aeabi_uidivmod, ...; assembly): the sum of every stack decrement in the function's code:
    push/stmdb sp! (4 B per register), vpush/vstmdb sp! (8 B per D, 4 B per S register),
    sub sp (#imm), str/strd with [sp, #-N]!. Releases (pop, add sp) are ignored, so a function
    that allocates on several paths is over-counted, never under. Any other write of sp
    (mov sp, rX; sub sp, rX; msr msp) makes the frame unknown: an error if it is reached.

Calls through pointers (GCC's __indirect_call, or the instructions above) are resolved by the
rules given: --indirect-from CALLER TARGET applies to callers whose name matches CALLER (when
one matches, the --indirect rules do not apply to that caller: a span routine that calls texel
fetchers through pointers must not have span routines as candidates, a false recursion);
--indirect TARGET to every other caller. Names are matched mangled and demangled. The
candidates are the functions that match TARGET and whose address the image takes: a word of a
loaded section that a relocation marks as an absolute address (R_ARM_ABS32/TARGET1: vtables,
tables of function pointers, literal pools; link with -Wl,--emit-relocs, else every word of
the image counts, which may take data for pointers) holding the function's address | 1, or a
movw/movt pair; no other function can be called through a pointer. The call costs the deepest
candidate; a rule without candidates (e.g. static constructors, with an empty .init_array)
costs 0. A caller with indirect calls and no rule is an error, and so is an address-taken
function that is no entry and no rule's candidate: a call through a pointer could reach it
uncounted. A function that nothing the analysis sees reaches (no call, branch, pointer or entry:
e.g. libgcc's __aeabi_ldiv0, entered through a computed `pop {pc}` on ARMv6-M) must have depth
0, or it is an error.

Exception handlers (--handler, or every vector but reset with --vector-table) are charged the
frame the core stacks on exception entry: 8 words (32 B), or 26 words (104 B) with an FP
context (the M4F's lazy stacking reserves it whenever the interrupted code used the FPU), plus
4 B when the SP was not 8-byte aligned (STKALIGN): 36 B, or 108 B when the image holds VFP
instructions; --exception-frame overrides. The total is the deepest thread-mode entry plus every
handler, as if all nested (no priorities are known): an upper bound.

For tests, --symbols FILE (lines "ADDR SIZE TYPE NAME [FILE]" in hexadecimal, every line a
function) and --disasm FILE (objdump -d text) stand in for the ELF; ELF may then be "-".
"""

from __future__ import annotations

import argparse
import bisect
import os
import re
import shutil
import struct
import subprocess
import sys
from dataclasses import dataclass, field


class StackError(Exception):
    """No sound bound: the message says which function and why."""


# ---------------------------------------------------------------------------------------------
# ELF (32-bit little-endian ARM): function symbols and the words of the loaded sections.

SHT_SYMTAB, SHT_NOBITS, SHT_REL = 2, 8, 9
R_ARM_ABS32, R_ARM_TARGET1 = 2, 38
SHF_ALLOC = 0x2
STT_FUNC, STT_FILE = 2, 4
STB_LOCAL, STB_GLOBAL = 0, 1


@dataclass
class Function:
    addr: int  # even: the Thumb bit cleared
    size: int  # 0 when the symbol has none (assembly): then it runs to the next function
    names: list  # every symbol at this address (aliases): global, then weak, then local ones
    ranks: list  # of each name: 0 global, 1 weak, 2 local
    file: str | None  # source file (FILE symbol) of a local-only function

    @property
    def local(self):
        return self.ranks[0] == 2


@dataclass
class Image:
    functions: dict  # address: Function
    words: dict | None = None  # address: every aligned 32-bit word of the loaded sections
    pointer_words: set | None = None  # addresses of the words that hold an absolute address
    #                                   (R_ARM_ABS32/TARGET1 relocations: --emit-relocs images)
    sections: dict = field(default_factory=dict)  # name: its 32-bit words (the vector table)


def read_elf(path):
    """The image's function symbols, loaded words, relocated words and sections."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x7fELF" or data[4] != 1 or data[5] != 1:
        raise StackError(f"{path}: not a 32-bit little-endian ELF")
    (shoff,) = struct.unpack_from("<I", data, 0x20)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x2E)
    sections, names = [], []
    for i in range(shnum):
        name, typ, flags, addr, off, size, link, info, _, entsize = struct.unpack_from(
            "<10I", data, shoff + i * shentsize)
        sections.append((typ, flags, addr, off, size, link, info, entsize))
        names.append(name)
    shstr = sections[shstrndx][3]
    section_words = {}  # name: its words, for the vector table
    for i, (typ, _, _, off, size, _, _, _) in enumerate(sections):
        name = data[shstr + names[i]:data.index(b"\0", shstr + names[i])].decode()
        if typ != SHT_NOBITS and size % 4 == 0:
            section_words[name] = struct.unpack_from(f"<{size // 4}I", data, off)
    words = {}
    for typ, flags, addr, off, size, _, _, _ in sections:
        if typ == SHT_NOBITS or not flags & SHF_ALLOC or size == 0:
            continue
        for a in range((addr + 3) & ~3, addr + size - 3, 4):
            (words[a],) = struct.unpack_from("<I", data, off + a - addr)
    pointer_words = None
    for typ, _, _, off, size, _, info, entsize in sections:
        if typ != SHT_REL or not sections[info][1] & SHF_ALLOC:
            continue
        pointer_words = pointer_words or set()
        for i in range(size // (entsize or 8)):
            r_offset, r_info = struct.unpack_from("<II", data, off + i * 8)
            if r_info & 0xFF in (R_ARM_ABS32, R_ARM_TARGET1):
                pointer_words.add(r_offset)
    functions = {}
    for typ, _, _, off, size, link, _, entsize in sections:
        if typ != SHT_SYMTAB:
            continue
        stroff = sections[link][3]

        def string(o):
            end = data.index(b"\0", stroff + o)
            return data[stroff + o:end].decode("utf-8", "replace")

        current_file = None
        for i in range(size // entsize):
            st_name, value, st_size, st_info, _, shndx = struct.unpack_from(
                "<IIIBBH", data, off + i * entsize)
            kind, bind = st_info & 0xF, st_info >> 4
            if kind == STT_FILE:
                current_file = string(st_name)
            elif kind == STT_FUNC and shndx != 0:
                rank = 2 if bind == STB_LOCAL else 0 if bind == STB_GLOBAL else 1
                add_function(functions, value & ~1, st_size, string(st_name), rank,
                             current_file if rank == 2 else None)
    return Image(functions, words, pointer_words, section_words)


def add_function(functions, addr, size, name, rank, file):
    f = functions.get(addr)
    if f is None:
        functions[addr] = Function(addr, size, [name], [rank], file)
        return
    f.size = max(f.size, size)
    if name in f.names:
        return
    i = sum(1 for r in f.ranks if r <= rank)  # stable: globals first (the .ci files' names)
    f.names.insert(i, name)
    f.ranks.insert(i, rank)
    if rank < 2:
        f.file = None


def function_ranges(functions):
    """Sorted starts and their ends; a function without a size ends where the next begins."""
    starts = sorted(functions)
    ends = []
    for i, s in enumerate(starts):
        size = functions[s].size
        nxt = starts[i + 1] if i + 1 < len(starts) else s + 4
        ends.append(s + size if size else nxt)
    return starts, ends


def read_symbols_file(path):
    """Test input: "ADDR SIZE TYPE NAME [FILE]" (hex); TYPE t local, W weak, T global."""
    functions = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts or parts[0].startswith("#"):
                continue
            addr, size, typ, name = int(parts[0], 16), int(parts[1], 16), parts[2], parts[3]
            rank = 2 if typ.islower() else 1 if typ == "W" else 0
            add_function(functions, addr & ~1, size, name, rank,
                         parts[4] if rank == 2 and len(parts) > 4 else None)
    return functions


# ---------------------------------------------------------------------------------------------
# GCC call-graph files (.ci, VCG).

NODE_RE = re.compile(r'^node:\s*\{\s*title:\s*"((?:[^"\\]|\\.)*)"\s*label:\s*"((?:[^"\\]|\\.)*)"')
EDGE_RE = re.compile(r'^edge:\s*\{\s*sourcename:\s*"((?:[^"\\]|\\.)*)"\s*'
                     r'targetname:\s*"((?:[^"\\]|\\.)*)"')
GRAPH_RE = re.compile(r'^graph:\s*\{\s*title:\s*"((?:[^"\\]|\\.)*)"')
FRAME_RE = re.compile(r"(\d+) bytes \(([a-z,]+)\)")
INDIRECT = "__indirect_call"


@dataclass
class CiNode:
    name: str  # assembler name
    source: str  # the translation unit's source file (the graph's title)
    ci_file: str
    frame: int
    qualifier: str
    callees: list = field(default_factory=list)  # (name, source file or None)
    indirect: bool = False


def split_title(title):
    """'path/file.cpp:name' (GCC prefixes local and some COMDAT nodes) -> (name, path)."""
    if ":" in title:
        path, name = title.rsplit(":", 1)
        return name, path
    return title, None


def parse_ci(path):
    """The functions a .ci file defines (nodes with a frame size), with their calls."""
    nodes = {}
    source = path
    with open(path, errors="replace") as f:
        for line in f:
            m = GRAPH_RE.match(line)
            if m:
                source = m.group(1)
                continue
            m = NODE_RE.match(line)
            if m:
                frame = FRAME_RE.search(m.group(2))
                if frame:  # external nodes (shape: ellipse) have none
                    name, _ = split_title(m.group(1))
                    nodes[m.group(1)] = CiNode(name, source, path, int(frame.group(1)),
                                               frame.group(2))
                continue
            m = EDGE_RE.match(line)
            if m and m.group(1) in nodes:
                node = nodes[m.group(1)]
                if m.group(2) == INDIRECT:
                    node.indirect = True
                else:
                    node.callees.append(split_title(m.group(2)))
    return list(nodes.values())


def image_ci_files(build_dir, map_file, elf_dir):
    """The .ci files of the objects the map file says the image was linked from; every .ci
    under build_dir without a map file."""
    build_dir = os.path.abspath(build_dir)
    all_ci = []
    for root, _, files in os.walk(build_dir):
        all_ci += [os.path.join(root, n) for n in files if n.endswith(".ci")]
    if not map_file:
        return sorted(all_ci)
    objects, members = set(), set()
    member_re = re.compile(r"^(\S+\.a)\(([^)]+)\)")
    with open(map_file, errors="replace") as f:
        for line in f:
            if line.startswith("LOAD "):
                objects.add(line[5:].strip())
            for m in member_re.finditer(line.strip()):
                members.add((m.group(1), m.group(2)))
    chosen = set()
    for obj in objects:
        if obj.endswith(".a"):
            continue
        p = os.path.normpath(os.path.join(elf_dir, obj))
        ci = os.path.splitext(p)[0] + ".ci"
        if os.path.exists(ci):
            chosen.add(ci)
    for archive, member in members:
        adir = os.path.normpath(os.path.dirname(os.path.join(elf_dir, archive)))
        want = os.path.splitext(member)[0] + ".ci"
        found = [c for c in all_ci if os.path.basename(c) == want and
                 c.startswith(adir + os.sep)]
        chosen.update(found)
    return sorted(chosen)


# ---------------------------------------------------------------------------------------------
# Disassembly (objdump -d --no-show-raw-insn).

INSN_RE = re.compile(r"^\s*([0-9a-f]+):\s+([a-z.][\w.]*)\s*(.*)$")
COND = "(?:eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le|al)"
BRANCH_RE = re.compile(rf"^b{COND}?(?:\.[nw])?$")
CALL_RE = re.compile(rf"^blx?{COND}?(?:\.[nw])?$")
TARGET_RE = re.compile(r"^([0-9a-f]+)\b")
REG_RE = re.compile(r"^(r\d+|ip|lr|sl|fp|sb)$")
LITERAL_RE = re.compile(r"^(r\d+|ip|sl|fp|sb),\s*\[pc,\s*#-?\d+\]\s*@\s*\(([0-9a-f]+)")
FP_MNEMONIC_RE = re.compile(r"^v[a-z]")


@dataclass
class CodeFacts:
    """What the disassembly says about one function."""
    calls: set = field(default_factory=set)  # target addresses
    tails: set = field(default_factory=set)
    indirect: list = field(default_factory=list)  # instruction texts
    jumps: list = field(default_factory=list)  # mov pc, rN: switch tables or indirect jumps
    frame: int = 0  # sum of the stack decrements
    unknown_sp: list = field(default_factory=list)  # instructions writing sp otherwise
    direct_literals: set = field(default_factory=set)  # literal words used as branch targets
    instructions: int = 0
    # A `sub sp, #N` as the function's first instruction, before its push: the bytes where it
    # stores arguments it received in registers (a by-value object split between registers and
    # the stack: GCC's "pretend args"), which GCC's .ci frame leaves out.
    first_sub: int = 0
    pretend: int = 0


def reg_count(reglist):
    """Registers in '{r4, r5, r8-r11, lr}' (ranges of r/d/s registers)."""
    n = 0
    for item in reglist.strip("{} ").split(","):
        item = item.strip()
        m = re.match(r"^([rds])(\d+)-[rds](\d+)$", item)
        n += int(m.group(3)) - int(m.group(2)) + 1 if m else (1 if item else 0)
    return n


def popped_registers(mnemonic, operands):
    if mnemonic.startswith("pop") or (mnemonic.startswith("ldm") and operands.startswith("sp!")):
        lst = operands[operands.index("{"):] if "{" in operands else ""
        return {r.strip() for r in lst.strip("{} ").split(",")}
    m = re.match(r"^(?:ldr(?:\.w)?)\s*$", mnemonic)
    if m and re.search(r"\[sp\]", operands):
        return {operands.split(",")[0].strip()}
    return set()


NO_WRITE = ("cmp", "cmn", "tst", "teq")


def stack_effect(mnemonic, operands):
    """Bytes an instruction pushes (> 0); None when it releases stack or leaves sp alone; -1
    when it writes sp in a way this analysis does not follow."""
    base = re.sub(rf"{COND}?(\.[nw])?$", "", mnemonic)
    ops = operands.split("@")[0].replace(" ", "").replace("\t", "")
    if mnemonic.startswith("push") or (base in ("stmdb", "stmfd") and ops.startswith("sp!")):
        return 4 * reg_count(ops[ops.index("{"):])
    if mnemonic.startswith("vpush") or (base == "vstmdb" and ops.startswith("sp!")):
        lst = ops[ops.index("{"):]
        return (8 if "d" in lst else 4) * reg_count(lst)
    if mnemonic.startswith(("pop", "vpop")) or (base.startswith(("ldm", "vldm")) and
                                                ops.startswith("sp!")):
        return None
    m = re.search(r"\[sp,#-(\d+)\]!", ops)
    if m and base.startswith("str"):
        return int(m.group(1))
    if base.startswith(("ldr", "str", "vldr", "vstr")) and not ops.startswith("sp,"):
        return None  # loads and stores (post-increment loads release)
    if base == "msr" and re.match(r"^(msp|psp)", ops, re.I):
        return -1
    if base in NO_WRITE or not re.match(r"^sp(,|$)", ops):
        return None  # sp is not the destination
    m = re.match(r"^sp,(?:sp,)?#(\d+)$", ops)
    if m and base in ("sub", "subw", "subs"):
        return int(m.group(1))
    if m and base in ("add", "addw", "adds"):
        return None
    return -1


def parse_disassembly(text, functions):
    """CodeFacts per function address, the movw/movt constants, and whether VFP code occurs."""
    starts, ends = function_ranges(functions)

    def containing(addr):
        i = bisect.bisect_right(starts, addr) - 1
        return starts[i] if i >= 0 and addr < ends[i] else None

    facts = {a: CodeFacts() for a in starts}
    constants, uses_fp = set(), False
    movw, popped, reg_branches, table = {}, {}, [], None
    prev = None  # (function, mnemonic, operands) of the previous instruction

    def flush_table(t):
        fn_, text_, words_ = t
        # The table is the run of words that point into the function; a literal pool may
        # follow it in the same run of .word lines (its length is not in the code).
        if not words_:
            facts[fn_].jumps.append(text_)
        elif containing(words_[0] & ~1) != fn_:
            facts[fn_].indirect.append(text_)

    for line in text.splitlines():
        m = INSN_RE.match(line)
        if not m:
            continue
        addr, mnemonic, operands = int(m.group(1), 16), m.group(2), m.group(3).strip()
        fn = containing(addr)
        if table and (fn != table[0] or mnemonic != ".word"):
            # `ldr pc, [rA, rB, lsl #2]` and the words after it: a switch when every word is an
            # address in the same function, else a branch through a pointer. With no words after
            # it the table is elsewhere (.rodata: GCC's ARMv8-M code): judged like mov pc, below.
            flush_table(table)
            table = None
        if table and mnemonic == ".word":
            table[2].append(int(operands.split()[0], 16))
            continue
        if fn is None or mnemonic.startswith("."):  # .word / .short: data in the code
            prev = None
            continue
        cf = facts[fn]
        cf.instructions += 1
        if FP_MNEMONIC_RE.match(mnemonic):
            uses_fp = True
        popped.setdefault(fn, set()).update(popped_registers(mnemonic, operands))
        effect = stack_effect(mnemonic, operands)
        if effect == -1:
            cf.unknown_sp.append(f"{addr:x}: {mnemonic} {operands}")
        elif effect:
            cf.frame += effect
            if cf.instructions == 1 and mnemonic.startswith("sub"):
                cf.first_sub = effect
            elif cf.instructions == 2 and cf.first_sub and not mnemonic.startswith("sub"):
                cf.pretend = cf.first_sub  # then the push of the saved registers
        mm = re.match(r"^(r\d+|ip|lr|sl|fp|sb),\s*#(\d+)", operands)
        if mm and mnemonic.startswith("movw"):
            movw[(fn, mm.group(1))] = int(mm.group(2))
        elif mm and mnemonic.startswith("movt") and (fn, mm.group(1)) in movw:
            constants.add((int(mm.group(2)) << 16) | movw[(fn, mm.group(1))])

        is_call = bool(CALL_RE.match(mnemonic))
        is_branch = bool(BRANCH_RE.match(mnemonic))
        t = TARGET_RE.match(operands)
        reg = operands.split("@")[0].strip()
        if (is_call or is_branch) and t:
            target = int(t.group(1), 16)
            own = containing(target) == fn
            if is_call and (not own or target == fn):  # bl to its own start: recursion
                cf.calls.add(target)
            elif is_branch and not own:
                cf.tails.add(target)
        elif mnemonic.startswith(("blx", "bx")) and REG_RE.match(reg):
            literal = None
            if prev and prev[0] == fn and prev[1].startswith("ldr"):
                lm = LITERAL_RE.match(prev[2])
                if lm and lm.group(1) == reg:
                    literal = int(lm.group(2), 16)
            if literal is not None:
                cf.direct_literals.add(literal)
                (cf.calls if mnemonic.startswith("blx") else cf.tails).add(("literal", literal))
            elif mnemonic.startswith("blx"):
                cf.indirect.append(f"{addr:x}: {mnemonic} {reg}")
            elif reg != "lr":
                reg_branches.append((fn, reg, f"{addr:x}: {mnemonic} {reg}"))
        elif mnemonic.startswith("ldr") and operands.startswith("pc,") and "[sp" not in operands:
            table = (fn, f"{addr:x}: {mnemonic} {operands}", [])
        elif mnemonic.startswith("mov") and operands.startswith("pc,") and reg != "pc, lr":
            cf.jumps.append(f"{addr:x}: {mnemonic} {operands}")
        prev = (fn, mnemonic, operands)
    if table:
        flush_table(table)
    # bx rN returns when rN was restored from the stack in the function (pop {..., r3}; bx r3),
    # otherwise it is a branch through a pointer.
    for fn, reg, text_ in reg_branches:
        if reg not in popped.get(fn, set()):
            facts[fn].indirect.append(text_)
    return facts, constants, uses_fp


# ---------------------------------------------------------------------------------------------
# Names.

def demangler(tool_prefix):
    for tool in (tool_prefix + "c++filt", "c++filt"):
        path = shutil.which(tool)
        if path:
            def run(names, path=path):
                if not names:
                    return {}
                out = subprocess.run([path], input="\n".join(names) + "\n", text=True,
                                     capture_output=True, check=True).stdout.splitlines()
                return dict(zip(names, out)) if len(out) == len(names) else {n: n for n in names}
            return run
    return lambda names: {n: n for n in names}


def short_name(demangled):
    """Without the parameter list: 'lr::Renderer<...>::render', 'foo [clone .part.0]'."""
    clone = ""
    m = re.search(r"( \[clone [^\]]+\])+$", demangled)
    if m:
        clone = " [" + ", ".join(re.findall(r"clone ([^\]]+)", m.group(0))) + "]"
        demangled = demangled[:m.start()]
    s = demangled
    for suffix in (" const", " volatile", " &", " &&"):
        if s.endswith(")" + suffix):
            s = s[:-len(suffix)]
    if s.endswith(")"):
        depth = 0
        for i in range(len(s) - 1, -1, -1):
            depth += {")": 1, "(": -1}.get(s[i], 0)
            if depth == 0:
                if i > 0:
                    s = s[:i]
                break
    return s + clone


# ---------------------------------------------------------------------------------------------
# The graph.

@dataclass
class Node:
    fn: Function
    frame: int | None = None
    frame_source: str = ""
    calls: set = field(default_factory=set)  # addresses
    tails: set = field(default_factory=set)
    indirect: list = field(default_factory=list)  # why (for messages); empty: none
    error: str | None = None


class Analysis:
    def __init__(self, functions, ci_nodes, facts, address_taken, literal_words, rules,
                 global_rules, demangle, jump_tables=frozenset()):
        self.functions = functions
        self.literal_words = literal_words  # {address: word} of the loaded sections
        self.by_name = {}
        for f in functions.values():
            for n in f.names:
                self.by_name.setdefault(n, []).append(f)
        self.demangled = demangle(sorted({n for f in functions.values() for n in f.names}))
        self.address_taken = address_taken  # None: unknown (no ELF)
        self.rules = rules  # [(caller_re, target_re)]
        self.global_rules = global_rules  # [target_re]
        self.jump_tables = jump_tables  # functions that image words point into: switch tables
        self.nodes = {a: Node(f) for a, f in functions.items()}
        self._attach_ci(ci_nodes)
        self._attach_code(facts)
        self.memo = {}

    # -- names
    def display(self, f):
        return short_name(self.demangled.get(f.names[0], f.names[0]))

    def matches(self, f, regex):
        return any(regex.search(n) or regex.search(self.demangled.get(n, n)) for n in f.names)

    def lookup(self, name, source=None, context=None):
        """The function a .ci callee name means: a unique name, or the local one of the source."""
        cands = self.by_name.get(name, [])
        if len(cands) <= 1:
            return cands[0] if cands else None
        for src in (source, context):
            if src:
                base = os.path.basename(src)
                hit = [f for f in cands if f.local and f.file and os.path.basename(f.file) == base]
                if len(hit) == 1:
                    return hit[0]
        glob = [f for f in cands if not f.local]
        return glob[0] if len(glob) == 1 else None

    # -- inputs
    def _attach_ci(self, ci_nodes):
        for cn in ci_nodes:
            f = self.lookup(cn.name, cn.source)
            if f is None:
                continue  # discarded by --gc-sections
            if f.local and f.file and os.path.basename(f.file) != os.path.basename(cn.source):
                continue  # a local function of the same name in another translation unit
            node = self.nodes[f.addr]
            if cn.qualifier == "dynamic":
                node.error = (f"{self.display(f)}: dynamic (unbounded) stack frame "
                              f"({cn.frame} B bounded part, {cn.ci_file})")
            if node.frame is None or cn.frame > node.frame:
                node.frame, node.frame_source = cn.frame, cn.ci_file
            if cn.indirect:
                node.indirect.append(f"indirect call ({cn.ci_file})")
            for name, src in cn.callees:
                callee = self.lookup(name, src, cn.source)
                if callee is None:
                    if name in self.by_name:
                        node.error = node.error or (
                            f"{self.display(f)}: calls {name}, which the image defines more "
                            f"than once (cannot tell which)")
                        continue
                    if name.startswith("__aeabi_"):
                        # A run-time helper GCC's call graph names from before its later passes
                        # (a signed 64-bit division that became an unsigned one, or went): an
                        # image that does not define it cannot call it (the link would fail), and
                        # every call that is there the disassembly adds (_attach_code).
                        continue
                    node.error = node.error or (f"{self.display(f)}: calls {name}, a function "
                                                f"the image does not define (unknown function)")
                    continue
                node.calls.add(callee.addr)

    def _attach_code(self, facts):
        starts, ends = function_ranges(self.functions)
        for addr, cf in facts.items():
            node = self.nodes[addr]
            if node.frame is None and cf.instructions:
                if cf.unknown_sp:
                    node.error = node.error or (
                        f"{self.display(node.fn)}: no .ci node and its code moves sp in a way "
                        f"this analysis does not follow: {cf.unknown_sp[0]}")
                node.frame, node.frame_source = cf.frame, "disassembly"
            elif cf.pretend:
                # The .ci frame without the pretend args the code reserves first.
                node.frame += cf.pretend
                node.frame_source += f" + {cf.pretend} B of arguments (disassembly)"
            code_calls, code_tails = set(), set()
            for kind, targets in (("call", cf.calls), ("tail", cf.tails)):
                for t in targets:
                    if isinstance(t, tuple):  # ("literal", address of the literal word)
                        t = self.literal_target(t[1])
                        if t is None:
                            node.indirect.append("branch through a literal that is no function")
                            continue
                    i = bisect.bisect_right(starts, t) - 1
                    callee = self.functions[starts[i]] if i >= 0 and t < ends[i] else None
                    if callee is None:
                        node.error = node.error or (
                            f"{self.display(node.fn)}: branches to {t:#x}, inside no function "
                            f"(unknown function)")
                        continue
                    cold = any(re.search(r"\.cold(\.\d+)?$", n) for n in callee.names)
                    if kind == "call" or cold or t != callee.addr:
                        code_calls.add(callee.addr)
                    else:
                        code_tails.add(callee.addr)
            # A .ci edge the code only branches to is a sibling call: GCC lists it as a call.
            node.calls = (node.calls - (code_tails - code_calls)) | code_calls
            node.tails = code_tails - node.calls
            node.indirect += [f"indirect branch `{i}`" for i in cf.indirect]
            # mov pc, rN is ARMv6-M's switch dispatch (through a table of addresses inside the
            # function); without such a table it is a jump through a pointer.
            if addr not in self.jump_tables:
                node.indirect += [f"indirect branch `{i}`" for i in cf.jumps]

    def literal_target(self, literal_addr):
        w = self.literal_words.get(literal_addr)
        if w is None or not w & 1 or (w & ~1) not in self.functions:
            return None
        return w & ~1

    # -- indirect calls
    def candidates(self, f):
        rules = [t for c, t in self.rules if self.matches(f, c)]
        if not rules:
            rules = self.global_rules
        if not rules:
            return None
        out = []
        for g in self.functions.values():
            if self.address_taken is not None and g.addr not in self.address_taken:
                continue
            if any(self.matches(g, t) for t in rules):
                out.append(g.addr)
        return out

    def check_coverage(self, entries):
        """Every address-taken function must be an entry or some rule's candidate."""
        if self.address_taken is None:
            return
        targets = [t for _, t in self.rules] + list(self.global_rules)
        for addr in sorted(self.address_taken):
            f = self.functions[addr]
            if addr in entries or any(self.matches(f, t) for t in targets):
                continue
            raise StackError(
                f"{self.display(f)}: its address is taken (a pointer to it is in the image) but "
                f"it is no entry and no --indirect/--indirect-from rule names it: a call through "
                f"a pointer could reach it uncounted")

    def check_orphans(self, entries):
        """A function in the image that no call, branch or pointer the analysis sees reaches was
        reached some other way (a computed branch): fine only if it cannot add stack, i.e. its
        depth is 0 (e.g. libgcc's __aeabi_ldiv0, `bx lr`, which ARMv6-M's __aeabi_uldivmod
        enters through a computed pop {pc})."""
        if self.address_taken is None:
            return
        reached = set(entries) | self.address_taken
        for node in self.nodes.values():
            reached |= node.calls | node.tails
        for addr in sorted(set(self.functions) - reached):
            d, _ = self.depth(addr)
            if d:
                raise StackError(
                    f"{self.display(self.functions[addr])}: in the image ({d} B deep) but no "
                    f"call, branch or pointer this analysis sees reaches it (unknown caller)")

    # -- depth
    def depth(self, addr, stack=()):
        """(bytes, path) of the deepest stack below a call of `addr` (its own frame included)."""
        if addr in self.memo:
            return self.memo[addr]
        node = self.nodes[addr]
        if addr in stack:
            cycle = list(stack[stack.index(addr):]) + [addr]
            raise StackError("recursion: " + " -> ".join(self.display(self.functions[a])
                                                         for a in cycle))
        if node.error:
            raise StackError(node.error)
        if node.frame is None:
            raise StackError(f"{self.display(node.fn)}: no frame size (no .ci node, no code)")
        stack = stack + (addr,)
        best, path = node.frame, []
        for callee in sorted(node.calls):
            d, p = self.depth(callee, stack)
            if node.frame + d > best:
                best, path = node.frame + d, p
        for callee in sorted(node.tails):
            d, p = self.depth(callee, stack)
            if d > best:
                best, path = d, p
        if node.indirect:
            cands = self.candidates(node.fn)
            if cands is None:
                raise StackError(f"{self.display(node.fn)}: unresolved {node.indirect[0]} (give "
                                 f"--indirect or --indirect-from for it)")
            for callee in sorted(cands):
                d, p = self.depth(callee, stack)
                if node.frame + d > best:
                    best, path = node.frame + d, ["*"] + p
        result = (best, [addr] + path)
        self.memo[addr] = result
        return result

    def print_frames(self, path):
        for a in path:
            if a != "*":
                node = self.nodes[a]
                kind = "tail-calls on" if any(b in node.tails for b in path) else ""
                print(f"  {node.frame:6,} B  {self.display(node.fn)}  "
                      f"[{os.path.basename(node.frame_source)}] {kind}".rstrip())

    def format_path(self, path):
        out, through_pointer = [], False
        for a in path:
            if a == "*":
                through_pointer = True
                continue
            name = self.display(self.functions[a])
            out.append(("(*) " if through_pointer else "") + name)
            through_pointer = False
        return " -> ".join(out)


def find_entry(analysis, name):
    hits = analysis.by_name.get(name) or [
        f for f in analysis.functions.values()
        if any(analysis.demangled.get(n) == name or short_name(analysis.demangled.get(n, n)) == name
               for n in f.names)]
    if not hits:
        raise StackError(f"entry {name}: no such function in the image (unknown function)")
    if len({f.addr for f in hits}) > 1:
        raise StackError(f"entry {name}: more than one function has this name")
    return hits[0].addr


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("elf", help="the image ('-' with --symbols and --disasm)")
    ap.add_argument("build_dir", help="where the objects' .ci files are")
    ap.add_argument("--entry", action="append", default=[],
                    help="thread-mode entry (default: Reset_Handler)")
    ap.add_argument("--handler", action="append", default=[],
                    help="exception handler: charged the exception entry frame")
    ap.add_argument("--indirect", action="append", default=[], metavar="TARGET_REGEX",
                    help="candidates of calls through pointers (callers without --indirect-from)")
    ap.add_argument("--indirect-from", action="append", nargs=2, default=[],
                    metavar=("CALLER_REGEX", "TARGET_REGEX"),
                    help="candidates of the calls through pointers in matching callers")
    ap.add_argument("--vector-table", metavar="SECTION",
                    help="take the entries from the vector table in SECTION (e.g. .isr_vector): "
                         "the reset vector as a thread entry, every other handler as --handler")
    ap.add_argument("--map", help="map file (default: ELF with .map, when it exists)")
    ap.add_argument("--exception-frame", type=int,
                    help="bytes stacked on exception entry (default: from the image's FPU use)")
    ap.add_argument("--tool-prefix", default="arm-none-eabi-")
    ap.add_argument("--symbols", help="test input instead of the ELF's symbol table")
    ap.add_argument("--disasm", help="test input instead of objdump -d of the ELF")
    ap.add_argument("--verbose", action="store_true",
                    help="list each path's functions with their frames and where they came from")
    ap.add_argument("--machine", action="store_true",
                    help="also print 'entry<TAB>bytes' lines, and 'total<TAB>bytes'")
    args = ap.parse_args(argv)

    try:
        if args.symbols:
            image = Image(read_symbols_file(args.symbols))
        else:
            image = read_elf(args.elf)
        functions, words = image.functions, image.words
        if args.disasm:
            with open(args.disasm) as f:
                disasm = f.read()
        elif args.elf != "-":
            disasm = subprocess.run([args.tool_prefix + "objdump", "-d", "--no-show-raw-insn",
                                     args.elf], capture_output=True, text=True, check=True).stdout
        else:
            disasm = ""
        map_file = args.map
        if map_file is None and args.elf != "-":
            candidate = os.path.splitext(args.elf)[0] + ".map"
            map_file = candidate if os.path.exists(candidate) else None
        elf_dir = os.path.dirname(os.path.abspath(args.elf)) if args.elf != "-" else "."
        ci_files = image_ci_files(args.build_dir, map_file, elf_dir)
        if not ci_files:
            raise StackError(f"no .ci files of this image under {args.build_dir} (was it built "
                             f"with -fcallgraph-info=su?)")
        ci_nodes = [n for path in ci_files for n in parse_ci(path)]
        facts, constants, uses_fp = parse_disassembly(disasm, functions)

        # Address-taken functions: the pointer words (every word without relocations, which
        # over-counts) holding a function's address | 1, and movw/movt constants. Literal words
        # that only feed a direct branch (ldr rN, =f; bx rN) take no address.
        address_taken, pointer_words = None, image.pointer_words
        if words is not None:
            used_for_branches = {lit for cf in facts.values() for lit in cf.direct_literals}
            where = pointer_words if pointer_words is not None else words.keys()
            address_taken = {words[a] & ~1 for a in where
                             if a in words and a not in used_for_branches and words[a] & 1 and
                             (words[a] & ~1) in functions}
            address_taken |= {c & ~1 for c in constants if c & 1 and (c & ~1) in functions}
            if pointer_words is None:
                print("stack_usage: note: no relocations in the ELF (link with "
                      "-Wl,--emit-relocs): every word of the image is taken for a possible "
                      "function pointer", file=sys.stderr)

        # Functions that words of the image point into (not at their start): switch tables.
        starts, ends = function_ranges(functions)
        jump_tables = set()
        for a in (pointer_words if pointer_words is not None else (words or {}).keys()):
            v = (words or {}).get(a, 0) & ~1
            i = bisect.bisect_right(starts, v) - 1
            if i >= 0 and starts[i] < v < ends[i]:
                jump_tables.add(starts[i])

        frame = args.exception_frame
        if frame is None:
            frame = (104 if uses_fp else 32) + 4
        analysis = Analysis(
            functions, ci_nodes, facts, address_taken, words or {},
            [(re.compile(c), re.compile(t)) for c, t in args.indirect_from],
            [re.compile(t) for t in args.indirect], demangler(args.tool_prefix), jump_tables)

        if args.vector_table:
            vectors = image.sections.get(args.vector_table)
            if not vectors or len(vectors) < 2:
                raise StackError(f"no vector table in section {args.vector_table}")
            reset = vectors[1] & ~1
            for i, v in enumerate(vectors[1:], start=1):
                f = functions.get(v & ~1)
                if v == 0:
                    continue
                if f is None:
                    raise StackError(f"vector {i} ({v:#x}) is no function of the image")
                name = f.names[0]
                target = args.entry if v & ~1 == reset else args.handler
                if name not in target:
                    target.append(name)
        entries = args.entry or ([] if args.handler else ["Reset_Handler"])
        entry_addrs = {name: find_entry(analysis, name) for name in entries + args.handler}
        analysis.check_coverage(set(entry_addrs.values()))
        analysis.check_orphans(set(entry_addrs.values()))

        thread_max = 0
        handler_sum = 0
        for name in entries:
            d, path = analysis.depth(entry_addrs[name])
            thread_max = max(thread_max, d)
            print(f"{name}: {d:,} B via {analysis.format_path(path)}")
            if args.verbose:
                analysis.print_frames(path)
            if args.machine:
                print(f"entry\t{name}\t{d}")
        for name in args.handler:
            d, path = analysis.depth(entry_addrs[name])
            handler_sum += d + frame
            print(f"{name}: {d + frame:,} B = {frame} B exception entry + {d:,} B via "
                  f"{analysis.format_path(path)}")
            if args.verbose:
                analysis.print_frames(path)
            if args.machine:
                print(f"handler\t{name}\t{d + frame}")
        fp_note = ("26 words with the FP context" if frame == 108 else
                   "8 words" if frame == 36 else "given")
        if args.handler:
            print(f"total: {thread_max + handler_sum:,} B (deepest thread entry {thread_max:,} B "
                  f"+ every handler nested on it; exception entry {frame} B = {fp_note} + 4 B "
                  f"alignment)")
        if args.machine:
            print(f"total\t{thread_max + handler_sum}")
        return 0
    except StackError as e:
        print(f"stack_usage: error: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
