#!/usr/bin/env python3
"""Every C example in docs/c-api.md compiles against capi/include/nearshore.h (issue 40).

The examples are fragments a host pastes into its own frame loop, so each ```c block becomes the
body of a function whose parameters are the host's handles the block uses without declaring
(sea, renderer, camera, width_px, height_px, dt, fleet), compiled with -Wall -Werror as C11.
Usage: compile_c_examples.py <c compiler> <repository root> <work folder>
"""
import re
import subprocess
import sys
from pathlib import Path

# The host's own variables an example may take for granted, and their types.
HOST_VARIABLES = {
    "sea": "nearshore_sea*",
    "renderer": "nearshore_renderer*",
    "camera": "nearshore_camera",
    "width_px": "int",
    "height_px": "int",
    "dt": "double",
    "fleet": "nearshore_fleet*",
}


def c_blocks(markdown: Path):
    """(line number, text) of each ```c block."""
    blocks, current, start = [], None, 0
    for number, line in enumerate(markdown.read_text().splitlines(), start=1):
        if current is None and line.strip() == "```c":
            current, start = [], number
        elif current is not None and line.strip().startswith("```"):
            blocks.append((start, "\n".join(current)))
            current = None
        elif current is not None:
            current.append(line)
    return blocks


def parameters_of(body: str):
    used = []
    for name, kind in HOST_VARIABLES.items():
        if not re.search(rf"\b{name}\b", body):
            continue
        declared = re.search(rf"\b(?:nearshore_\w+|double|int|float)\s*\**\s*{name}\s*[;=\[]", body)
        if not declared:
            used.append(f"{kind} {name}")
    return ", ".join(used) if used else "void"


def main():
    cc, root, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    markdown = root / "docs" / "c-api.md"
    blocks = c_blocks(markdown)
    if not blocks:
        print(f"{markdown}: no ```c blocks found")
        return 1
    failures = 0
    for start, body in blocks:
        source = work / f"c_api_example_line_{start}.c"
        indented = "\n".join("  " + line for line in body.splitlines())
        source.write_text(
            "#include <stdio.h>\n#include <string.h>\n#include \"nearshore.h\"\n\n"
            f"/* docs/c-api.md line {start} */\nvoid example_line_{start}({parameters_of(body)}) {{\n{indented}\n}}\n")
        result = subprocess.run([cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-Wno-unused-parameter",
                                 "-I", str(root / "capi" / "include"), "-c", str(source), "-o", str(source.with_suffix(".o"))],
                                capture_output=True, text=True)
        if result.returncode == 0:
            print(f"ok   docs/c-api.md:{start}")
        else:
            failures += 1
            print(f"FAIL docs/c-api.md:{start} does not compile ({source}):\n{result.stderr}")
    print(f"{len(blocks)} C examples, {failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
