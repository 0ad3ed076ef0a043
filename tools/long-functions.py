#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""long-functions.py [--max N] [PATH...]: lists the functions of host/ and cl/ (C, C++, OpenCL C)
longer than N lines (default 80), longest first, and prints their count. A function is a top-level
brace block whose opening line (or the lines just before it) has a parameter list: struct, enum and
initialiser blocks are skipped. Counts lines from the signature to the closing brace. Comments and
strings are blanked first so that braces inside them do not count. A review aid for STYLE.md's
"short functions" (issue 33), not a test."""
import argparse
import os
import re
import sys

CODE = (".c", ".h", ".cc", ".cl")


def blank_comments_and_strings(text):
    def keep_newlines(m):
        return re.sub(r"[^\n]", " ", m.group(0))
    pattern = r'//[^\n]*|/\*.*?\*/|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\''
    return re.sub(pattern, keep_newlines, text, flags=re.S)


def functions(path):
    lines = blank_comments_and_strings(open(path, errors="replace").read()).split("\n")
    depth, start = 0, None
    for i, line in enumerate(lines):
        for ch in line:
            if ch == "{":
                if depth == 0:
                    head = " ".join(lines[max(0, i - 3):i + 1])
                    head = head[:head.rfind("{")]
                    is_function = re.search(r"\)\s*(const\s*)?$", head.strip()) is not None and \
                        not re.search(r"\b(struct|enum|union)\b[^()]*$", head) and "=" not in head.split("(")[0]
                    start = None
                    if is_function:
                        # the signature starts at the first line of the statement that ends here
                        s = i
                        while s > 0 and lines[s - 1].strip() and not lines[s - 1].rstrip().endswith((";", "}", "*/")) \
                                and not lines[s - 1].lstrip().startswith("#"):
                            s -= 1
                        start = s
                depth += 1
            elif ch == "}":
                depth -= 1
                if depth == 0 and start is not None:
                    name = re.findall(r"(\w+)\s*\(", " ".join(lines[start:i + 1]))
                    yield (name[0] if name else "?"), start + 1, i - start + 1
                    start = None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--max", type=int, default=80)
    ap.add_argument("paths", nargs="*", default=["host", "cl"])
    a = ap.parse_args()
    found = []
    for root in a.paths:
        for d, _, files in os.walk(root):
            for f in sorted(files):
                if f.endswith(CODE):
                    p = os.path.join(d, f)
                    found += [(n, p, line, name) for name, line, n in functions(p) if n > a.max]
    for n, p, line, name in sorted(found, reverse=True):
        print(f"{n:5d}  {p}:{line}  {name}")
    print(f"long-functions: {len(found)} functions over {a.max} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
