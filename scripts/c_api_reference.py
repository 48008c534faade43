#!/usr/bin/env python3
"""Writes docs/c-api-reference.md from capi/include/nearshore.h: every function (its declaration, its
comment, its thread rule), every struct and enum (as declared, with their field comments), every
opaque handle, section by section as the header orders them. The header is the source; this page
is generated, and the test c_api_reference_is_current fails when the two differ.

Usage: c_api_reference.py [--check] [repository root]   (--check: compare, write nothing)
"""
import re
import sys
from pathlib import Path

HEADER = Path("capi/include/nearshore.h")
PAGE = Path("docs/c-api-reference.md")


def strip_comment(text):
    """The words of a /* ... */ block without its markers and leading stars."""
    text = re.sub(r"^/\*+", "", text.strip())
    text = re.sub(r"\*+/$", "", text)
    lines = [re.sub(r"^\s*\*\s?", "", line).rstrip() for line in text.splitlines()]
    return "\n".join(lines).strip()


def thread_rule(doc):
    if re.search(r"\bany\s+thread\b", doc, re.I):
        return "any thread"
    if re.search(r"\brender\s+thread\b", doc, re.I):
        return "render thread"
    return ""


def parse(header_text):
    """Items in header order: ('section', title, doc), ('function', name, declaration, doc),
    ('type', name, declaration, doc), ('handle', name, doc), ('preamble', doc), ('define', text, doc)."""
    items, pending = [], ""
    lines = header_text.splitlines()
    i = 0
    first_comment = True
    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        if stripped.startswith("/*"):
            block = [line]
            while "*/" not in lines[i]:
                i += 1
                block.append(lines[i])
            doc = strip_comment("\n".join(block))
            i += 1
            if first_comment:
                items.append(("preamble", doc))
                first_comment = False
                continue
            section = re.match(r"-{3,}\s*(.*?)\s*-{3,}\s*(.*)$", doc, re.S)
            if section:
                items.append(("section", section.group(1), section.group(2).strip()))
                pending = ""
            else:
                pending = doc
            continue
        if stripped.startswith("NEARSHORE_API ") and not stripped.startswith("#"):
            declaration = [stripped]
            while not declaration[-1].rstrip().endswith(";"):
                i += 1
                declaration.append(lines[i].strip())
            text = " ".join(declaration)
            name = re.search(r"(nearshore_\w+)\s*\(", text).group(1)
            items.append(("function", name, text.replace("NEARSHORE_API ", ""), pending))
            pending = ""
            i += 1
            continue
        handle = re.match(r"typedef struct (\w+) (\w+);", stripped)
        if handle:
            items.append(("handle", handle.group(2), pending))
            pending = ""
            i += 1
            continue
        if re.match(r"typedef (struct|enum) \w+ \{", stripped):
            body = [line]
            while not re.match(r"\}\s*\w+;", lines[i].strip()):
                i += 1
                body.append(lines[i])
            name = re.match(r"\}\s*(\w+);", lines[i].strip()).group(1)
            items.append(("type", name, "\n".join(body), pending))
            pending = ""
            i += 1
            continue
        if stripped.startswith("typedef "):
            name = re.search(r"\(\*(\w+)\)", stripped)
            items.append(("type", name.group(1) if name else stripped, stripped, pending))
            pending = ""
            i += 1
            continue
        if stripped.startswith("#define NEARSHORE_API_VERSION"):
            items.append(("define", stripped, pending))
            pending = ""
        elif stripped:
            pending = ""  # a comment belongs only to the declaration right under it
        i += 1
    return items


def render(items):
    out = ["# C API reference (`nearshore.h`)", "",
           "Generated from `capi/include/nearshore.h` by `scripts/c_api_reference.py`; do not edit: change the",
           "header's comments and run `python3 scripts/c_api_reference.py`. The guide is docs/c-api.md;",
           "the samples are in samples/.", ""]
    # A section may state one rule for all its calls ("Every fleet call is render thread").
    section_rule, functions = "", []
    for item in items:
        if item[0] == "section":
            section_rule = thread_rule(item[2])
        elif item[0] == "function":
            functions.append((*item[:3], item[3], thread_rule(item[3]) or section_rule))
    rule_of = {name: rule for _, name, _, _, rule in functions}
    for kind, *rest in items:
        if kind == "preamble":
            out += ["## Conventions", "", "```text", rest[0], "```", ""]
        elif kind == "define":
            text, doc = rest
            out += ["## Version", "", "```c", text, "```", ""]
            if doc:
                out += ["```text", doc, "```", ""]
            out += ["## Functions", "", "| function | thread | |", "|---|---|---|"]
            for _, name, _, doc, rule in functions:
                summary = re.split(r"(?<=\.)\s", doc.replace("\n", " "), maxsplit=1)[0] if doc else ""
                out.append(f"| [`{name}`](#{name}) | {rule or '-'} | {summary.replace('|', '/')} |")
            out.append("")
        elif kind == "section":
            title, doc = rest
            out += [f"## {title[0].upper() + title[1:]}", ""]
            if doc:
                out += [doc, ""]
        elif kind == "handle":
            name, doc = rest
            out += [f"### `{name}` (opaque handle)", ""]
            if doc:
                out += [doc, ""]
        elif kind == "type":
            name, declaration, doc = rest
            out += [f"### `{name}`", ""]
            if doc:
                out += [doc, ""]
            out += ["```c", declaration, "```", ""]
        elif kind == "function":
            name, declaration, doc = rest
            out += [f"### `{name}`", "", "```c", declaration, "```", ""]
            rule = rule_of[name]
            if doc:
                out += [doc, ""]
            out += [f"Thread: {rule}." if rule else "Thread: not stated in the header (a bug: report it).", ""]
    return "\n".join(out).rstrip() + "\n"


def main(arguments):
    check = "--check" in arguments
    rest = [a for a in arguments if a != "--check"]
    root = Path(rest[0]) if rest else Path(__file__).resolve().parent.parent
    page = render(parse((root / HEADER).read_text()))
    target = root / PAGE
    if check:
        if not target.exists() or target.read_text() != page:
            print(f"{target} is not what {root / HEADER} generates: run `python3 scripts/c_api_reference.py` "
                  "and commit docs/c-api-reference.md")
            return 1
        functions = page.count("\n### `nearshore_") 
        print(f"{target}: current ({functions} entries)")
        return 0
    target.write_text(page)
    print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
