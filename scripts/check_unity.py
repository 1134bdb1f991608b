#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks that the .cpp files of one library can be compiled as one unity translation unit.

CMake's unity build (CMakeLists.txt, AQ_UNITY) compiles the .cpp files of a library a batch at a
time as one translation unit. Names with internal linkage then meet: two files' `namespace { ... }`
helpers of the same name are a redefinition error when their signatures agree (loud), but an
overload when they differ, and a call in the later file may silently pick the earlier file's
function. A `using namespace` or a `#define` left at file scope reaches the files after it.

This script is run by CMake at configure time for every unity-built library and fails (exit 1),
naming the files, when:
  - a name is declared with internal linkage (at the top level of an anonymous namespace, or
    `static` at namespace scope) in two files of the library;
  - a file has a `using namespace` directive outside any function or class;
  - a file #defines a macro it does not #undef.
The fix is mechanical: rename one of the helpers (or move a shared one into a header), put the
using-directive inside the function, #undef the macro at the end of the file.

  scripts/check_unity.py LIBRARY FILE.cpp...
"""
import re
import sys

KEYWORDS = {
    "if", "for", "while", "switch", "return", "sizeof", "alignof", "decltype", "static_assert",
    "operator", "template", "typename", "const", "constexpr", "inline", "static", "struct",
    "class", "enum", "union", "namespace", "using", "noexcept", "explicit", "void", "auto",
}


def strip(text):
    """Removes comments, string and character literals (keeps line structure)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text.startswith('R"', i) and re.match(r'R"([^(\s]*)\(', text[i:]):
            delim = re.match(r'R"([^(\s]*)\(', text[i:]).group(1)
            j = text.find(")" + delim + '"', i)
            j = n if j < 0 else j + len(delim) + 2
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def split_top(text, sep=","):
    """Splits at `sep` outside parentheses, brackets, braces and angle brackets."""
    parts, depth, cur = [], 0, []
    for ch in text:
        if ch in "([{<":
            depth += 1
        elif ch in ")]}>" and depth > 0:
            depth -= 1
        if ch == sep and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    parts.append("".join(cur))
    return parts


def first_name(item):
    """The identifier before the first '(', '=', '{' or '[' at angle depth 0 ("" if none)."""
    depth = 0
    for k, ch in enumerate(item + ";"):
        if ch == "<":
            depth += 1
        elif ch == ">" and depth > 0:
            depth -= 1
        elif depth == 0 and ch in "(={[;":
            m = re.search(r"(\w+)\s*$", item[:k])
            if m and m.group(1) not in KEYWORDS and not m.group(1)[0].isdigit():
                return m.group(1)
            return ""
    return ""


def declared_names(item):
    """The names an item at namespace scope declares, as (name, text) pairs: text is the whole
    declaration for aliases (two files may declare the same alias to the same thing), else ""."""
    item = re.sub(r"template\s*<[^{};]*?>\s*", "", item)  # template heads (no nested braces)
    m = re.match(r"\s*(?:struct|class|union|enum(?:\s+class|\s+struct)?)\s+(\w+)", item)
    if m:
        return [(m.group(1), "")]
    m = re.match(r"\s*(?:using|namespace)\s+(\w+)\s*=", item)
    if m:
        return [(m.group(1), " ".join(item.split()))]
    if re.match(r"\s*(?:using|namespace|enum)\b", item):
        return []
    parts = split_top(item)
    names = [first_name(parts[0])]
    # More declarators of one declaration: `constexpr int kA = 1, kB = 2;`
    names += [first_name(p) for p in parts[1:] if re.match(r"\s*\w+\s*[={[]", p)]
    return [(n, "") for n in names if n]


def scan(path):
    """(internal names, problems) of one file."""
    raw = open(path, encoding="utf-8").read()
    text = strip(raw)
    problems = []
    defined = re.findall(r"^\s*#\s*define\s+(\w+)", text, re.M)
    undefined = set(re.findall(r"^\s*#\s*undef\s+(\w+)", text, re.M))
    # A default (`#ifndef X` then `#define X`) is the same in every file that has it.
    defaults = set(re.findall(r"^\s*#\s*ifndef\s+(\w+)\s*\n\s*#\s*define\s+\1\b", text, re.M))
    for macro in defined:
        if macro not in undefined and macro not in defaults:
            problems.append(f"#define {macro} without #undef {macro} at the end of the file")
    text = re.sub(r"^\s*#.*$", "", text, flags=re.M)  # preprocessor lines
    names = set()
    # Walk the braces: a stack of scopes, each "ns" (a named namespace), "anon" (an anonymous
    # one) or "other" (a class, function or initialiser body).
    stack, item = [], []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "{":
            head = "".join(item)
            at_ns = all(s != "other" for s in stack)
            if at_ns and re.search(r"\bnamespace\s*$", head):
                stack.append("anon")
            elif at_ns and re.search(r"\bnamespace\s+[\w:]+\s*$", head):
                stack.append("ns")
            else:
                if at_ns:
                    record(head, stack, names)
                    if "anon" in stack and re.match(r"\s*enum\b(?!\s+(?:class|struct)\b)", head):
                        # An unscoped enum: its enumerators are names of the namespace.
                        body = text[i + 1 : text.find("}", i)]
                        for e in split_top(body):
                            m = re.match(r"\s*(\w+)", e)
                            if m:
                                names.add((m.group(1), ""))
                stack.append("other")
            item = []
        elif c == "}":
            if stack:
                stack.pop()
            item = []
        elif c == ";":
            if all(s != "other" for s in stack):
                head = "".join(item)
                if re.match(r"\s*using\s+namespace\b", head):
                    problems.append(f"file-scope `{head.strip()};` (put it inside the functions that use it)")
                record(head, stack, names)
            item = []
        else:
            item.append(c)
        i += 1
    return names, problems


def record(head, stack, names):
    anon = "anon" in stack
    static = re.match(r"\s*(?:template\s*<[^{};]*?>\s*)?static\b", head) is not None
    if not anon and not static:
        return
    for entry in declared_names(head):
        names.add(entry)


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    library, files = sys.argv[1], sys.argv[2:]
    owners, problems = {}, []
    for f in files:
        names, bad = scan(f)
        problems += [f"{f}: {p}" for p in bad]
        for name, text in names:
            owners.setdefault(name, []).append((f, text))
    for name, decl in sorted(owners.items()):
        fs = sorted({f for f, _ in decl})
        same_alias = all(t and t == decl[0][1] for _, t in decl)
        if len(fs) > 1 and not same_alias:
            problems.append(f"`{name}` has internal linkage in {len(fs)} files: {', '.join(fs)}")
    if problems:
        print(f"unity build of {library}: these would meet in one translation unit "
              "(scripts/check_unity.py explains; rename one, share it through a header, or build with "
              "-DAQ_UNITY=OFF):")
        for p in problems:
            print("  " + p)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
