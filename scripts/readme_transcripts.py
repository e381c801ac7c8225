#!/usr/bin/env python3
"""Re-runs the README's `$ solsim ...` blocks and rewrites the ones that drifted.

    python3 scripts/readme_transcripts.py [--solsim PATH] [--check]

The commands run in README order in a scratch directory linked to the repository (as
tests/issue_28_readme_figures.rs runs them), a `/tmp/...` path in a temporary directory. A block
without `...` lines (the ellipsis character) is replaced by what the command prints now. A block
with them (lines left out) is not rewritten: the script prints the command's whole output so the
kept lines can be chosen by hand. `--check` rewrites nothing and exits 1 if a block drifted.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ELLIPSIS = "\u2026"


def without_durations(lines):
    """"in 88.1 s" and "on 2 threads" are the machine's: not compared (as the test does)."""
    text = "\n".join(lines)
    text = re.sub(r"(?<= in )\d+(\.\d+)?(?= s\b)", "<s>", text)
    return re.sub(r"(?<= on )\d+(?= threads?\b)", "<n>", text)


def blocks(lines):
    """(index of the first command line, index of the closing fence) of each `$ solsim` block."""
    i = 0
    while i < len(lines):
        if lines[i].startswith("```") and i + 1 < len(lines) and lines[i + 1].startswith("$ solsim "):
            j = i + 1
            while not lines[j].startswith("```"):
                j += 1
            yield i + 1, j
            i = j
        i += 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--solsim", default=str(ROOT / "target/release/solsim"))
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    args.solsim = str(Path(args.solsim).resolve())
    readme = ROOT / "README.md"
    lines = readme.read_text().split("\n")
    work = tempfile.mkdtemp(prefix="readme-")
    tmp = tempfile.mkdtemp(prefix="readme-tmp-")
    for entry in ROOT.iterdir():
        if entry.name not in ("target", "solsim-out", ".git"):
            os.symlink(entry, Path(work) / entry.name)
    out = []
    last = 0
    drifted = 0
    for start, end in blocks(lines):
        out.extend(lines[last:start])
        k = start
        while k < end:
            cmd = lines[k][2:]
            body_end = k + 1
            while body_end < end and not lines[body_end].startswith("$ "):
                body_end += 1
            body = lines[k + 1:body_end]
            argv = [a.replace("/tmp/", tmp + "/", 1) if a.startswith("/tmp/") else a
                    for a in cmd.split()[1:]]
            done = subprocess.run([args.solsim, *argv], cwd=work, capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit(f"README line {k + 1}: `{cmd}` failed:\n{done.stderr}")
            printed = done.stdout.replace(tmp + "/", "/tmp/").rstrip("\n").split("\n")
            out.append(lines[k])
            if any(ELLIPSIS in b for b in body):
                out.extend(body)
                print(f"--- README line {k + 1}: `{cmd}` (has left-out lines; choose by hand):")
                print("\n".join(printed))
            else:
                if without_durations(body) == without_durations(printed):
                    printed = body
                else:
                    drifted += 1
                    print(f"README line {k + 1}: `{cmd}` drifted", file=sys.stderr)
                out.extend(printed)
            k = body_end
        last = end
    out.extend(lines[last:])
    if args.check:
        sys.exit(1 if drifted else 0)
    if drifted:
        readme.write_text("\n".join(out))
        print(f"rewrote {drifted} blocks", file=sys.stderr)


if __name__ == "__main__":
    main()
