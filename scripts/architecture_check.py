#!/usr/bin/env python3
"""The architecture rules of ARCHITECTURE.md, checked (issue 29). Exit 1 on any breach.

1. **No import circle between the files of a crate.** A file `uses` another when it names a
   path into it (`use crate::a::b::X`, `crate::a::f()`, `super::x`): file A → file B. A circle
   is a strongly connected set of two or more files. A parent file naming its own child modules
   (`mod x; pub use x::Y;`) is a declaration, not a use. Tests (`#[cfg(test)]` and everything
   after it in a file) are left out: a test module may name whatever it tests.
2. **No source file over 600 lines** (up to its first `#[cfg(test)]`), but for the files in
   LONG_FILES, each named with why it is one concept.
3. **The binary crate (src/) under 3000 lines** in all, counted the same way.

    scripts/architecture_check.py            # every crate of the workspace
"""
import os
import re
import sys
from pathlib import Path

PATH = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP = re.compile(r"\buse\s+(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)*)::\{", re.S)


def strip(text):
    """Source without comments, string literals and test modules."""
    cut = text.find("#[cfg(test)]")
    if cut >= 0:
        text = text[:cut]
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    return text


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
    files = sorted(src.rglob("*.rs"))
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
    """Lines up to the file's first `#[cfg(test)]`."""
    n = 0
    for line in path.read_text().splitlines():
        if line.startswith("#[cfg(test)]"):
            break
        n += 1
    return n


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
        for f in sorted(src.rglob("*.rs")):
            rel = str(f.relative_to(root))
            n = code_lines(f)
            if n > MAX_FILE_LINES and rel not in LONG_FILES:
                breaches += 1
                print(f"{rel}: {n} lines (over {MAX_FILE_LINES}, tests not counted)")
    binary = sum(code_lines(f) for f in (root / "src").rglob("*.rs"))
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
