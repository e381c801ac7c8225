#!/usr/bin/env python3
"""The architecture rules of ARCHITECTURE.md, checked (issue 29). Exit 1 on any breach.

1. **No import circle between the files of a crate.** A file `uses` another when it names a
   path into it (`use crate::a::b::X`, `crate::a::f()`, `super::x`): file A → file B. A circle
   is a strongly connected set of two or more files. A parent file naming its own child modules
   (`mod x; pub use x::Y;`) is a declaration, not a use. Tests are left out (a test module may
   name whatever it tests): every item marked `#[cfg(test)]` wherever it stands (a `mod tests
   { … }`, a `use`, a helper), a file under `#![cfg(test)]`, and a file its parent declares
   `#[cfg(test)] mod x;`. Comments, strings and char literals are blanked first.
2. **No source file over 600 lines** (every line but those of its test items), but for the
   files in LONG_FILES, each named with why it is one concept.
3. **The binary crate (src/) under 3000 lines** in all, counted the same way.

    scripts/architecture_check.py            # every crate of the workspace
"""
import os
import re
import sys
from pathlib import Path

PATH = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"\buse\s+(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{", re.S)


def blank(text):
    """`text` with the insides of comments, string literals and char literals turned into
    spaces, newlines kept: same length, same line numbers, so what is left is code."""
    out, i, n = list(text), 0, len(text)

    def clear(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            clear(i, j)
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            clear(i, j)
            i = j
        elif (m := re.compile(r'b?r(#*)"').match(text, i)) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = text.find('"' + m.group(1), m.end())
            end = n if end < 0 else end + 1 + len(m.group(1))
            clear(m.end(), end - 1 - len(m.group(1)))
            i = end
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            clear(i + 1, j)
            i = j + 1
        elif c == "'":
            # A char literal ('x', '\n', '\u{..}'), not a lifetime ('a).
            m = re.compile(r"'(?:\\(?:u\{[0-9A-Fa-f]+\}|x[0-9A-Fa-f]{2}|.)|[^\\'\n])'").match(text, i)
            if m:
                clear(i + 1, m.end() - 1)
                i = m.end()
            else:
                i += 1
        else:
            i += 1
    return "".join(out)


ITEM_ENDS_AT_SEMICOLON = re.compile(r"\s*(?:pub(?:\([^)]*\))?\s+)?(?:use|const|static|type|extern\s+crate)\b")
CFG_TEST = re.compile(r"#\[cfg\(test\)\]")


def test_spans(code):
    """The spans of `code` (blanked) that are tests: each item marked `#[cfg(test)]` (a
    `mod tests { … }`, a `use`, a helper fn), from the attribute to the item's end; the whole
    file under `#![cfg(test)]`. Returns [(start, end, name of a `mod x;` declared there)]."""
    if re.search(r"#!\[cfg\(test\)\]", code):
        return [(0, len(code), None)]
    spans = []
    for m in CFG_TEST.finditer(code):
        if spans and m.start() < spans[-1][1]:
            continue
        i = m.end()
        # Further attributes of the same item.
        while True:
            a = re.compile(r"\s*#\[").match(code, i)
            if not a:
                break
            depth, i = 1, a.end()
            while i < len(code) and depth:
                depth += (code[i] == "[") - (code[i] == "]")
                i += 1
        semicolon_only = bool(ITEM_ENDS_AT_SEMICOLON.match(code, i))
        decl = re.compile(r"\s*(?:pub(?:\([^)]*\))?\s+)?mod\s+([A-Za-z_][A-Za-z0-9_]*)\s*;").match(code, i)
        depth, j = 0, i
        while j < len(code):
            ch = code[j]
            if ch in "([{":
                depth += 1
            elif ch in ")]}":
                depth -= 1
                if depth == 0 and ch == "}" and not semicolon_only:
                    j += 1
                    break
            elif ch == ";" and depth == 0:
                j += 1
                break
            j += 1
        spans.append((m.start(), j, decl.group(1) if decl else None))
    return spans


def without_tests(text):
    """`text` blanked (see `blank`) and with its test items blanked too."""
    code = blank(text)
    out = list(code)
    for a, b, _ in test_spans(code):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "
    return "".join(out)


def strip(text):
    """Source without comments, string literals and test items."""
    return without_tests(text)


def module_of(src_root, f):
    rel = f.relative_to(src_root).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] in ("lib", "main", "mod"):
        parts = parts[:-1]
    return tuple(parts)


def group_paths(text, start):
    """The paths inside a `use a::b::{...}` group starting at `start` (after the brace)."""
    depth, i, buf = 1, start, ""
    while i < len(text) and depth:
        c = text[i]
        depth += (c == "{") - (c == "}")
        buf += c
        i += 1
    out, prefix = [], []

    def walk(s, pre):
        items, depth, cur = [], 0, ""
        for c in s:
            if c == "{":
                depth += 1
            elif c == "}":
                depth -= 1
            if c == "," and depth == 0:
                items.append(cur)
                cur = ""
            else:
                cur += c
        items.append(cur)
        for it in items:
            it = it.strip()
            if not it:
                continue
            if "{" in it:
                head, rest = it.split("{", 1)
                walk(rest[: rest.rfind("}")], pre + [p for p in head.strip(": ").split("::") if p])
            else:
                out.append(pre + [p for p in it.split(" as ")[0].strip().split("::") if p])

    walk(buf[:-1], prefix)
    return out


def crate_graph(crate_dir):
    src = Path(crate_dir) / "src"
    tests = test_files(src)
    files = sorted(f for f in src.rglob("*.rs") if f not in tests)
    modules = {module_of(src, f): f for f in files}
    edges = {f: set() for f in files}

    def resolve(here, kind, parts):
        if kind == "crate":
            base = []
        elif kind == "self":
            base = list(here)
        else:  # super
            base = list(here[:-1])
            while parts and parts[0] == "super":
                base, parts = base[:-1], parts[1:]
        path = base + parts
        # The longest prefix that is a file of this crate.
        for n in range(len(path), 0, -1):
            if tuple(path[:n]) in modules:
                return modules[tuple(path[:n])]
        return None

    for f in files:
        here = module_of(src, f)
        text = strip(f.read_text())
        refs = []
        for m in PATH.finditer(text):
            refs.append((m.group(1), [p for p in m.group(2).split("::") if p]))
        for m in USE_GROUP.finditer(text):
            head = [p for p in m.group(2).split("::") if p]
            for tail in group_paths(text, m.end()):
                refs.append((m.group(1), head + tail))
        for kind, parts in refs:
            target = resolve(here, kind, parts)
            if target and target != f:
                # A file naming its own child module (`mod x;` then `x::…`) is not an import;
                # naming an ancestor's item is (the ancestor is a file too).
                edges[f].add(target)
    # A parent file declares its children (`mod x;`): that is not a use.
    for f in files:
        here = module_of(src, f)
        edges[f] = {t for t in edges[f] if module_of(src, t)[: len(here)] != here or here == ()}
        if here == ():
            edges[f] = set()
    return src, edges


def circles(edges):
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


MAX_FILE_LINES = 600
MAX_BINARY_LINES = 3000

# Files allowed over MAX_FILE_LINES: path -> why it is one concept.
LONG_FILES = {
}


def code_lines(path):
    """Lines of the file that hold anything but tests: every line but those wholly inside a
    `#[cfg(test)]` item (comments and blank lines between code count)."""
    text = path.read_text()
    code = blank(text)
    starts = [0] + [k + 1 for k, ch in enumerate(text) if ch == "\n"]
    if starts[-1] == len(text):
        starts.pop()
    test_lines = set()
    for a, b, _ in test_spans(code):
        first = text.count("\n", 0, a)
        # The line of the span's start counts as a test line when nothing precedes it there.
        if text[starts[first]:a].strip():
            first += 1
        last = text.count("\n", 0, max(a, b - 1))
        if b < len(text) and text[b:text.find("\n", b) if text.find("\n", b) >= 0 else len(text)].strip():
            last -= 1
        test_lines.update(range(first, last + 1))
    return len(starts) - len(test_lines)


def test_files(src):
    """Files that are test modules: declared `#[cfg(test)] mod x;` by their parent."""
    out = set()
    for f in src.rglob("*.rs"):
        here = f.parent if f.name in ("lib.rs", "main.rs", "mod.rs") else f.with_suffix("")
        for _, _, name in test_spans(blank(f.read_text())):
            if name:
                for child in (here / f"{name}.rs", here / name / "mod.rs"):
                    if child.exists():
                        out.add(child)
    return out


def workspace_crates(root):
    text = (root / "Cargo.toml").read_text()
    members = re.search(r"members\s*=\s*\[([^\]]*)\]", text).group(1)
    return [m.strip().strip('"') for m in members.split(",") if m.strip()]


def main():
    # SOLSIM_ROOT: check another tree (the test suite checks the check on a planted copy).
    root = Path(os.environ.get("SOLSIM_ROOT") or Path(__file__).resolve().parent.parent)
    crates = sys.argv[1:] or workspace_crates(root)
    breaches = 0
    for crate in crates + ["."]:
        src = root / crate / "src"
        name = "solsim (src/)" if crate == "." else crate
        _, edges = crate_graph(root / crate)
        for comp in circles(edges):
            breaches += 1
            print(f"{name}: import circle between {', '.join(str(p.relative_to(src)) for p in comp)}")
            for a in comp:
                for b in sorted(edges[a]):
                    if b in comp:
                        print(f"    {a.relative_to(src)} -> {b.relative_to(src)}")
        for f in sorted(set(src.rglob("*.rs")) - test_files(src)):
            rel = str(f.relative_to(root))
            n = code_lines(f)
            if n > MAX_FILE_LINES and rel not in LONG_FILES:
                breaches += 1
                print(f"{rel}: {n} lines (over {MAX_FILE_LINES}, tests not counted)")
    binary = sum(code_lines(f) for f in set((root / "src").rglob("*.rs")) - test_files(root / "src"))
    if binary >= MAX_BINARY_LINES:
        breaches += 1
        print(f"src/ (the binary crate): {binary} lines (must stay under {MAX_BINARY_LINES})")
    print(
        f"{breaches} breach(es); binary crate {binary} lines; "
        f"{len(LONG_FILES)} file(s) over {MAX_FILE_LINES} lines allowed by name"
    )
    return 1 if breaches else 0


if __name__ == "__main__":
    sys.exit(main())
