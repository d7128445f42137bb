#!/usr/bin/env python3
"""Checks the links of the project's Markdown files: every relative link must name a file of the
repository, and every #anchor a heading of its target (GitHub's slugs: lower case, punctuation
dropped, spaces to hyphens). Also flags `tests/...::Suite.Name` references whose test does not
exist in that file, so that docs/raster-rules.md keeps naming real tests, and checks that a fenced
code block announced by `<!-- file: PATH -->` on the line before it is that file, byte for byte
(the README's example cannot drift from examples/); `<!-- file: PATH region: NAME -->` names the
lines between `// readme:begin NAME` and `// readme:end NAME` in PATH instead, without their
common indentation. Every ```cpp block of README.md must be one of these, so that each is code
that CI compiles and runs (examples/host: tests/examples). And flags a path that leaves the
repository (`../shared/x.md`), in a link, in backticks or in the text.

Usage: scripts/check_doc_links.py [FILE.md ...]   (default: README.md and docs/**/*.md)
Exit status 1 on any broken link or test reference, with one line per problem.

A document holding `<!-- every test of: PATH -->` must also name every test of PATH
(docs/api-errors.md: one row per test of tests/core/api_errors_test.cpp, none left out).
"""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
INCLUDED = re.compile(r"<!-- file: ([\w/.-]+)(?: region: ([\w-]+))? -->\n```\w*\n(.*?)^```$",
                      re.S | re.M)
CPP_BLOCK = re.compile(r"^```cpp$", re.M)
OUTSIDE = re.compile(r"(?<![\w./-])((?:\.\./)+[\w.-][\w./-]*)")
TEST_REF = re.compile(r"`(tests/[\w/.-]+\.cpp)::(\w+)\.(\w+)`|`::(\w+)\.(\w+)`")
EVERY_TEST = re.compile(r"<!-- every test of: ([\w/.-]+\.cpp) -->")


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path):
    out, seen = set(), {}
    in_code = False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                in_code = not in_code
            if in_code:
                continue
            m = re.match(r"#{1,6} (.*)", line)
            if m:
                base = slug(m.group(1))
                n = seen.get(base, 0)
                seen[base] = n + 1
                out.add(base if n == 0 else f"{base}-{n}")
    return out


def tests_in(path):
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return None
    return set(re.findall(r"^TEST(?:_F|_P)?\((\w+),\s*(\w+)\)", text, re.M))


def check(md):
    problems = []
    text = open(md, encoding="utf-8").read()
    # Links (outside code blocks).
    body = re.sub(r"```.*?```", "", text, flags=re.S)
    for m in LINK.finditer(body):
        target = m.group(1) or m.group(2)
        if re.match(r"[a-z]+://", target) or target.startswith("mailto:"):
            continue
        path, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(os.path.dirname(md), path)) if path else md
        if not os.path.exists(full):
            problems.append(f"{os.path.relpath(md, ROOT)}: no file {target}")
            continue
        if anchor and full.endswith(".md") and anchor not in anchors(full):
            problems.append(f"{os.path.relpath(md, ROOT)}: no heading #{anchor} in {path or 'itself'}")
    # Test references: `tests/x_test.cpp::Suite.Name`, and `::Suite.Name` for the last file named.
    last = None
    named = set()
    for m in TEST_REF.finditer(text):
        if m.group(1):
            last, suite, name = m.group(1), m.group(2), m.group(3)
        else:
            suite, name = m.group(4), m.group(5)
        if last is None:
            continue
        named.add((last, suite, name))
        found = tests_in(os.path.join(ROOT, last))
        if found is None:
            problems.append(f"{os.path.relpath(md, ROOT)}: no test file {last}")
        elif (suite, name) not in found:
            problems.append(f"{os.path.relpath(md, ROOT)}: no test {suite}.{name} in {last}")
    # Files whose every test the document must name.
    for path in EVERY_TEST.findall(text):
        found = tests_in(os.path.join(ROOT, path))
        if found is None:
            problems.append(f"{os.path.relpath(md, ROOT)}: no test file {path}")
            continue
        for suite, name in sorted(found):
            if (path, suite, name) not in named:
                problems.append(f"{os.path.relpath(md, ROOT)}: {path}'s test {suite}.{name} "
                                "is not named here")
    return problems


def region(text, name):
    """The lines between `// readme:begin NAME` and `// readme:end NAME`, dedented; None if the
    markers are missing."""
    m = re.search(rf"^[ \t]*// readme:begin {re.escape(name)}\n(.*?)^[ \t]*// readme:end "
                  rf"{re.escape(name)}$", text, re.S | re.M)
    if not m:
        return None
    lines = m.group(1).splitlines(keepends=True)
    indent = min((len(l) - len(l.lstrip(" ")) for l in lines if l.strip()), default=0)
    return "".join(l[indent:] if l.strip() else l.lstrip(" ") for l in lines)


def check_included(md):
    problems = []
    rel = os.path.relpath(md, ROOT)
    with open(md, encoding="utf-8") as f:
        text = f.read()
    covered = set()
    for m in INCLUDED.finditer(text):
        covered.add(text.index("```", m.start()))
        path = os.path.join(ROOT, m.group(1))
        if not os.path.isfile(path):
            problems.append(f"{rel}: no file {m.group(1)} for its code block")
            continue
        with open(path, encoding="utf-8") as f:
            source = f.read()
        if m.group(2):
            want = region(source, m.group(2))
            if want is None:
                problems.append(f"{rel}: no region '{m.group(2)}' (// readme:begin/end) in "
                                f"{m.group(1)}")
            elif want != m.group(3):
                problems.append(f"{rel}: the code block differs from region '{m.group(2)}' of "
                                f"{m.group(1)} (copy the region into it)")
        elif source != m.group(3):
            problems.append(f"{rel}: the code block differs from {m.group(1)} (copy the file "
                            f"into it)")
    # README's C++ must be compiled code: every ```cpp block an included file or region.
    if rel == "README.md":
        for m in CPP_BLOCK.finditer(text):
            if m.start() not in covered:
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{rel}:{line}: a ```cpp block that is not an included file or "
                                f"region (<!-- file: PATH [region: NAME] -->): CI would not "
                                f"compile it")
    return problems


def check_outside(md):
    """Paths that leave the repository (`../shared/...`) or, climbing with `../`, name nothing in
    it: in links, backticks or text, outside code blocks (a shell block may say `cd ..`)."""
    problems = []
    rel = os.path.relpath(md, ROOT)
    with open(md, encoding="utf-8") as f:
        text = f.read()
    body = re.sub(r"```.*?```", lambda b: "\n" * b.group(0).count("\n"), text, flags=re.S)
    for m in OUTSIDE.finditer(body):
        full = os.path.normpath(os.path.join(os.path.dirname(md), m.group(1)))
        line = body.count("\n", 0, m.start()) + 1
        if os.path.relpath(full, ROOT).startswith(".."):
            problems.append(f"{rel}:{line}: {m.group(1)} is outside the repository")
        elif not os.path.exists(full.rstrip(".")):
            problems.append(f"{rel}:{line}: {m.group(1)} names nothing in the repository")
    return problems


def main():
    files = sys.argv[1:] or [os.path.join(ROOT, "README.md")] + sorted(
        glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True))
    problems = []
    for md in files:
        md = os.path.abspath(md)
        problems += check(md) + check_included(md) + check_outside(md)
    for p in problems:
        print(p)
    print(f"check_doc_links: {len(files)} files, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
