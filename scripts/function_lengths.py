#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Lists the functions of C++ files by length, longest first, and checks a limit.

app/ is the thin orchestrator (ARCHITECTURE, STYLE): no function there above ~100 lines; a longer
one is a pipeline of its own, to be split into named steps or moved to the stage it belongs to.
This script keeps that true: ctest runs it on src/app with --max 100 (tests/CMakeLists.txt).

A function is a brace block at namespace or class scope whose declaration has a parameter list
(free functions, member functions defined in a class, constructors); its length counts the lines
from the first line of its declaration (a template<> line included) to its closing brace, blank
and comment lines included. Lambdas count as part of the function that holds them. Comments and
string literals are stripped first (scripts/check_unity.py's strip), so braces in them do not count.

  scripts/function_lengths.py [--max N] [--top K] PATH...   (files or folders of .cpp/.hpp)

Prints "LINES  FILE:LINE  NAME" for every function (or the K longest), then exits 1 naming the
functions above N lines when --max is given and any is.
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_unity import strip  # noqa: E402

SCOPES = re.compile(r"\b(namespace|class|struct|union|enum)\b")


def functions(path):
    """Yields (first line, last line, name) of every function defined in the file `path`."""
    with open(path, encoding="utf-8") as f:
        text = strip(f.read())
    stack = []  # per open brace: "scope" (namespace / class body), "function" or "block"
    decl_start = 0  # offset where the current declaration at scope level began
    for i, ch in enumerate(text):
        if ch == "{":
            if all(s[0] == "scope" for s in stack):
                decl = text[decl_start:i]
                head = decl.split("(")[0]
                if "(" in decl and not SCOPES.search(head) and "=" not in head and not head.rstrip().endswith("]"):
                    start = decl_start + len(decl) - len(decl.lstrip())
                    name = re.findall(r"[~\w:]+(?=\s*$)", head)
                    stack.append(("function", text.count("\n", 0, start) + 1, name[0] if name else "?"))
                else:
                    stack.append(("scope" if SCOPES.search(decl) or decl.strip().startswith('extern ""') else "block",))
            else:
                stack.append(("block",))
            decl_start = i + 1
        elif ch == "}":
            top = stack.pop() if stack else ("block",)
            if top[0] == "function":
                yield top[1], text.count("\n", 0, i) + 1, top[2]
            decl_start = i + 1
        elif ch == ";" and all(s[0] == "scope" for s in stack):
            decl_start = i + 1
        elif ch == ":" and all(s[0] == "scope" for s in stack):
            # an access specifier (public:) ends what came before it; a scope (a::b) does not
            before = text[decl_start:i].strip()
            if before in ("public", "private", "protected"):
                decl_start = i + 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("paths", nargs="+")
    ap.add_argument("--max", type=int, default=None, help="exit 1 when a function is longer than this")
    ap.add_argument("--top", type=int, default=None, help="print only the K longest")
    a = ap.parse_args()
    files = []
    for p in a.paths:
        if os.path.isdir(p):
            for root, _, names in os.walk(p):
                files += [os.path.join(root, n) for n in names if n.endswith((".cpp", ".hpp"))]
        else:
            files.append(p)
    rows = []
    for path in sorted(files):
        for first, last, name in functions(path):
            rows.append((last - first + 1, f"{path}:{first}", name))
    rows.sort(key=lambda r: (-r[0], r[1]))
    for n, where, name in rows[: a.top] if a.top else rows:
        print(f"{n:5d}  {where}  {name}")
    if a.max is not None:
        over = [r for r in rows if r[0] > a.max]
        if over:
            print(f"{len(over)} function(s) above {a.max} lines: "
                  + ", ".join(f"{name} ({n}, {where})" for n, where, name in over), file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
