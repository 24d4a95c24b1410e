#!/usr/bin/python3
"""The sizes the house keeps (issue 34): every header of src/ and include/ with its line count, and
the files and functions over the limits: headers over 250 lines, .c files over 500, functions over
100 (a function: a definition whose opening brace stands alone at column 0, as clang-format writes
them, to the closing brace at column 0).
  scripts/sizes.py [--check]     --check: exit 1 when something is over its limit"""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIMITS = {"header": 250, "source": 500, "function": 100}


def functions(path):
    """(name, first line, lines) of every function defined in a C file"""
    lines = open(path).read().split("\n")
    out, start, name = [], None, None
    for i, line in enumerate(lines):
        if line == "{" and i > 0:
            # the signature: back to the line that starts the declaration
            j = i - 1
            while j > 0 and not re.match(r"^[A-Za-z_]", lines[j]):
                j -= 1
            m = re.search(r"([A-Za-z_][A-Za-z0-9_]*)\s*\(", " ".join(lines[j:i]))
            start, name = i, m.group(1) if m else "?"
        elif line.startswith("}") and start is not None:
            out.append((name, start + 1, i - start + 1))
            start = None
    return out


def main():
    rel = lambda p: os.path.relpath(p, ROOT)
    headers = sorted(glob.glob(os.path.join(ROOT, "src", "**", "*.h"), recursive=True) +
                     glob.glob(os.path.join(ROOT, "include", "*.h")))
    sources = sorted(glob.glob(os.path.join(ROOT, "src", "**", "*.c"), recursive=True))
    over = []
    print("headers (limit %d lines):" % LIMITS["header"])
    for h in headers:
        n = open(h).read().count("\n")
        print("  %5d %s%s" % (n, rel(h), "  OVER" if n > LIMITS["header"] else ""))
        if n > LIMITS["header"]:
            over.append("%s: %d lines" % (rel(h), n))
    print(".c files over %d lines:" % LIMITS["source"])
    for s in sources:
        n = open(s).read().count("\n")
        if n > LIMITS["source"]:
            print("  %5d %s" % (n, rel(s)))
            over.append("%s: %d lines" % (rel(s), n))
    print("functions over %d lines:" % LIMITS["function"])
    for s in sources:
        for name, line, n in functions(s):
            if n > LIMITS["function"]:
                print("  %5d %s:%d %s" % (n, rel(s), line, name))
                over.append("%s:%d %s: %d lines" % (rel(s), line, name, n))
    print("%d over the limits" % len(over))
    if "--check" in sys.argv and over:
        sys.exit(1)


main()
