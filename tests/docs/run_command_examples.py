#!/usr/bin/env python3
"""Runs every shell example in docs/commands/*.md as written (issue 14 item 8).

A page's examples are its fenced blocks whose info string starts with `sh` (or `bash`); plain
fences are synopses and printed output, `toml`/`json` blocks are file excerpts. A block whose info
string also says `interactive` (opens a window and waits for the user) or `setup` (installs
packages on a fresh machine: README command 1, which CI itself runs) is listed and not run.

The examples run from a scratch copy of the repository's layout: `data/` and `../shared` as in a
checkout, `./build/release/tools/nearshore` and a bare `nearshore` on PATH both the binary under
test. demo.md runs first (the other pages use its demo-out/), then the rest alphabetically; the
blocks of one page run in order in one scratch folder, so a page may build on its earlier blocks.

Also checked: every command's `--help` names a "More:" page that exists, with the section its
anchor names.

Usage: run_command_examples.py NEARSHORE_BINARY SOURCE_DIR WORK_DIR [PAGE.md ...]
"""
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

BLOCK_TIMEOUT_S = 900
SKIP_WORDS = {"interactive": "opens a window and waits for the user",
              "setup": "installs packages on a fresh machine (README command 1, run by CI itself)"}


def fenced_blocks(page: Path):
    """(first line number, info string, text) of each fenced block of a Markdown page."""
    blocks, inside, info, start, lines = [], False, "", 0, []
    for number, line in enumerate(page.read_text().splitlines(), start=1):
        if line.startswith("```"):
            if not inside:
                inside, info, start, lines = True, line[3:].strip(), number + 1, []
            else:
                blocks.append((start, info, "\n".join(lines) + "\n"))
                inside = False
        elif inside:
            lines.append(line)
    if inside:
        raise SystemExit(f"{page}:{start - 1}: a fenced block is never closed; close it with ```")
    return blocks


def heading_anchors(page: Path):
    """GitHub's anchors of a page's headings: lower case, punctuation dropped, spaces to '-'."""
    anchors = set()
    for line in page.read_text().splitlines():
        match = re.match(r"^#+\s+(.*)$", line)
        if match:
            text = re.sub(r"[^\w\- ]", "", match.group(1).strip().lower())
            anchors.add(text.replace(" ", "-"))
    return anchors


def check_help_links(binary: str, source: Path):
    """Every command's and subcommand's --help ends with 'More: docs/...md[#anchor]' that exists."""
    problems = []

    def subcommands(args):
        text = subprocess.run([binary, *args, "--help"], capture_output=True, text=True).stdout
        names = []
        if "Subcommands:" in text:
            for line in text.split("Subcommands:", 1)[1].splitlines()[1:]:
                match = re.match(r"^  (\S+)\s", line)
                if not match:
                    if line.strip() == "":
                        if names:
                            break
                        continue
                    continue
                names.append(match.group(1))
        return text, names

    queue = [[]]
    while queue:
        args = queue.pop(0)
        text, names = subcommands(args)
        queue.extend(args + [name] for name in names)
        if not args:
            continue
        match = re.search(r"More: (\S+)", text)
        where = "nearshore " + " ".join(args) + " --help"
        if not match:
            problems.append(f"{where}: names no 'More:' page")
            continue
        link = match.group(1)
        path, _, anchor = link.partition("#")
        page = source / path
        if not page.is_file():
            problems.append(f"{where}: links {link}, but {path} does not exist")
        elif anchor and anchor not in heading_anchors(page):
            problems.append(f"{where}: links {link}, but {path} has no heading with the anchor #{anchor}")
    return problems


def prepare_scratch(binary: str, source: Path, work: Path):
    repo = work / "repo"
    if work.exists():
        shutil.rmtree(work)
    (repo / "build" / "release" / "tools").mkdir(parents=True)
    os.symlink(os.path.abspath(binary), repo / "build" / "release" / "tools" / "nearshore")
    os.symlink(source / "data", repo / "data")
    shared = (source / ".." / "shared").resolve()
    if shared.is_dir():
        os.symlink(shared, work / "shared")
    bin_dir = work / "bin"
    bin_dir.mkdir()
    os.symlink(os.path.abspath(binary), bin_dir / "nearshore")
    return repo, bin_dir


def main():
    if len(sys.argv) < 4:
        raise SystemExit(__doc__)
    binary, source, work = sys.argv[1], Path(sys.argv[2]).resolve(), Path(sys.argv[3]).resolve()
    pages = sorted((source / "docs" / "commands").glob("*.md"))
    if len(sys.argv) > 4:
        pages = [source / "docs" / "commands" / name for name in sys.argv[4:]]
    pages.sort(key=lambda page: (page.name != "demo.md", page.name))

    failures = check_help_links(binary, source)
    for problem in failures:
        print(f"FAIL {problem}")

    repo, bin_dir = prepare_scratch(binary, source, work)
    env = dict(os.environ, PATH=f"{bin_dir}:{os.environ.get('PATH', '')}")
    ran = skipped = 0
    for page in pages:
        relative = page.relative_to(source)
        for line, info, text in fenced_blocks(page):
            words = info.split()
            if not words or words[0] not in ("sh", "bash"):
                continue
            skip = [SKIP_WORDS[w] for w in words[1:] if w in SKIP_WORDS]
            if skip:
                skipped += 1
                print(f"skip {relative}:{line} ({skip[0]})")
                continue
            script = work / f"example_{page.stem}_{line}.sh"
            script.write_text("set -euo pipefail\n" + text)
            started = time.monotonic()
            try:
                result = subprocess.run(["bash", str(script)], cwd=repo, env=env, capture_output=True, text=True,
                                        timeout=BLOCK_TIMEOUT_S)
                status, output = result.returncode, result.stdout + result.stderr
            except subprocess.TimeoutExpired as timeout:
                status = "timeout"
                output = (timeout.stdout or b"").decode(errors="replace") + (timeout.stderr or b"").decode(errors="replace")
            seconds = time.monotonic() - started
            ran += 1
            if status == 0:
                print(f"ok   {relative}:{line} ({seconds:.1f} s)")
                continue
            failures.append(f"{relative}:{line}")
            tail = "\n".join(output.splitlines()[-40:])
            print(f"FAIL {relative}:{line} (exit status {status} after {seconds:.1f} s); the example:\n{text}"
                  f"its last output:\n{tail}\n")
    print(f"{ran} examples run, {skipped} not run (listed above), {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
