#!/usr/bin/env python3
"""Re-run the examples of README.md and docs/*.md and compare what they print.

An example is a ```text block whose lines starting with `$ ` are commands; the lines after a
command, up to the next command or the end of the block, are what it prints (standard output and
standard error together). Each command runs under bash in a scratch folder holding copies of
`configs/`, `tables/`, `include/`, `examples/` and `python/examples/` (so nothing in the checkout is written), with `target/release` and
`target/release/examples` first on PATH, so `sweep` and the Rust examples are the binaries under
test. A command whose first word is `git` (a `git grep` that counts the files a change touches)
runs in the repository itself instead, and only reads it.

A code block whose opening fence is preceded by a line `<!-- file: PATH -->` shows the file PATH
(relative to the repository root) and must equal it, so that the code shown is the code that
runs.

Times (`3.362 ms`, `52.9 s`), dates and commit hashes vary from run to run and are compared as
placeholders; progress lines (those with an `ETA`) depend on the machine's speed and are left
out; every other character must match.

It also refuses development history in tracked files (an issue's number, a found/fixed
table): that goes to CHANGELOG.md.

    python3 scripts/check_docs.py            # check; exit 1 and a diff on any difference
    python3 scripts/check_docs.py --update   # rewrite the blocks with what the commands print
"""

import argparse
import difflib
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

VOLATILE = [
    (re.compile(r"\b\d+(\.\d+)?(e-?\d+)? ?(ms|µs|ns|s)\b"), "<time>"),
    (re.compile(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ"), "<date>"),
    (re.compile(r"\bcommit [0-9a-f]{7,40}(-dirty)?…?"), "commit <hash>"),
    (re.compile(r"\bon \d+ threads\b"), "on <n> threads"),
]


PROGRESS = re.compile(r"\bETA\b")

# Development history (an issue's number, a found/fixed table) belongs in CHANGELOG.md and git, not in
# the files people read for what the code does.
NARRATIVE = re.compile(r"\bissues? #?\d+\b|\|\s*found\s*\|\s*fixed\s*\|", re.IGNORECASE)


def narrative():
    """Lines of tracked files (CHANGELOG.md aside) that tell development history; 0 or 1."""
    files = subprocess.run(
        ["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True
    ).stdout.decode().split("\0")
    found = 0
    for name in files:
        if not name or name == "CHANGELOG.md":
            continue
        try:
            text = (ROOT / name).read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            continue
        for number, line in enumerate(text.splitlines(), 1):
            if NARRATIVE.search(line):
                print(f"check_docs: {name}:{number}: development history (to CHANGELOG.md): {line}")
                found = 1
    return found


def normalise(text):
    for pattern, placeholder in VOLATILE:
        text = pattern.sub(placeholder, text)
    lines = text.rstrip("\n").split("\n")
    return [line.rstrip() for line in lines if not PROGRESS.search(line)]


def examples(path):
    """(start, end, indent, [(command, expected_lines)]) for each ```text block with commands."""
    lines = path.read_text(encoding="utf-8").split("\n")
    out, i = [], 0
    while i < len(lines):
        if lines[i].strip() == "```text":
            j = i + 1
            while j < len(lines) and lines[j].strip() != "```":
                j += 1
            # A block indented under a list item: its lines carry the fence's indentation.
            indent = lines[i][: len(lines[i]) - len(lines[i].lstrip())]
            body = [line[len(indent) :] if line.startswith(indent) else line for line in lines[i + 1 : j]]
            runs = []
            for line in body:
                if line.startswith("$ "):
                    runs.append((line[2:], []))
                elif runs:
                    runs[-1][1].append(line)
            if runs:
                out.append((i + 1, j, indent, runs))
            i = j
        i += 1
    return lines, out


SHOWN = re.compile(r"^\s*<!-- file: (\S+) -->\s*$")


def shown_files(path, update):
    """Check (or with `update` rewrite) the code blocks that show a file; the number of
    differences."""
    lines = path.read_text(encoding="utf-8").split("\n")
    failures, changed, i = 0, False, 0
    while i < len(lines):
        m = SHOWN.match(lines[i])
        if m and i + 1 < len(lines) and lines[i + 1].lstrip().startswith("```"):
            j = i + 2
            while j < len(lines) and lines[j].strip() != "```":
                j += 1
            fence = lines[i + 1]
            indent = fence[: len(fence) - len(fence.lstrip())]
            source = ROOT / m.group(1)
            want = source.read_text(encoding="utf-8").rstrip("\n").split("\n")
            want = [(indent + line) if line else line for line in want]
            if lines[i + 2 : j] != want:
                where = f"{path.relative_to(ROOT)}:{i + 2}"
                if update:
                    lines[i + 2 : j] = want
                    changed = True
                    j = i + 2 + len(want)
                else:
                    failures += 1
                    print(f"check_docs: {where}: the block differs from {m.group(1)}:")
                    diff = difflib.unified_diff(lines[i + 2 : j], want, "shown", m.group(1), lineterm="")
                    print("\n".join(diff))
            i = j
        i += 1
    if changed:
        path.write_text("\n".join(lines), encoding="utf-8")
        print(f"check_docs: updated {path.relative_to(ROOT)} from the files it shows")
    return failures


def run(command, scratch, env):
    # `git` commands read the repository (the scratch folder is none); the rest run in scratch.
    where = ROOT if command.split()[:1] == ["git"] else scratch
    r = subprocess.run(
        ["bash", "-o", "pipefail", "-c", command],
        cwd=where,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=600,
    )
    return r.returncode, r.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--update", action="store_true", help="rewrite the blocks with the output")
    args = ap.parse_args()
    sweep = ROOT / "target" / "release" / "sweep"
    if not sweep.exists():
        sys.exit(f"check_docs: {sweep} not built (run scripts/sweep --version or scripts/test)")
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(sweep.parent), str(sweep.parent / "examples"), env.get("PATH", "")])
    failures, count = narrative(), 0
    with tempfile.TemporaryDirectory(prefix="check_docs-") as scratch:
        for folder in ("configs", "tables", "python/examples", "include", "examples"):
            shutil.copytree(ROOT / folder, Path(scratch) / folder)
        (Path(scratch) / "docs").mkdir()
        for path in DOCS:
            failures += shown_files(path, args.update)
            lines, blocks = examples(path)
            changed = False
            for start, end, indent, runs in reversed(blocks):
                new_body = []
                for command, expected in runs:
                    count += 1
                    code, output = run(command, scratch, env)
                    where = f"{path.relative_to(ROOT)}:{start}"
                    if code != 0:
                        print(f"check_docs: {where}: `{command}` exited {code}:\n{output}")
                        failures += 1
                    got = output.rstrip("\n").split("\n") if output.strip() else []
                    got = [line for line in got if not PROGRESS.search(line)]
                    differs = normalise("\n".join(expected)) != normalise("\n".join(got))
                    if differs:
                        failures += not args.update
                        if not args.update:
                            diff = difflib.unified_diff(
                                expected, got, "documented", "printed now", lineterm=""
                            )
                            print(f"check_docs: {where}: `{command}` prints otherwise:")
                            print("\n".join(diff))
                    # --update keeps a block whose only differences are times and dates.
                    new_body += [f"$ {command}", *(got if args.update and differs else expected)]
                new_body = [(indent + line).rstrip() if line else line for line in new_body]
                if args.update and lines[start:end] != new_body:
                    lines[start:end] = new_body
                    changed = True
            if changed:
                path.write_text("\n".join(lines), encoding="utf-8")
                print(f"check_docs: updated {path.relative_to(ROOT)}")
    if failures:
        sys.exit(f"check_docs: {failures} of {count} documented commands differ")
    print(f"check_docs: {count} documented commands print what the docs show")


if __name__ == "__main__":
    main()
