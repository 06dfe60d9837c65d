#!/usr/bin/env python3
"""Replaces the section of benchmarks/hw.md (or the file given with --file) that starts with the
heading given (its `## ` line's beginning) by the text on standard input, up to the next `## `
heading; appends it when there is none. With --keep-others OLD instead of a heading: appends each
section of OLD whose heading line the file lacks. The bench scripts' one section writer."""
import re
import sys

args = sys.argv[1:]
path = "benchmarks/hw.md"
if args[:1] == ["--file"]:
    path, args = args[1], args[2:]
if args[:1] == ["--keep-others"]:
    # --keep-others OLD: append each section of OLD whose heading the file lacks (a script that
    # writes the whole file keeps the sections other scripts write)
    def sections(text):
        return [p for p in re.split(r"(?m)^(?=## )", text) if p.startswith("## ")]
    text = open(path).read()
    have = {s.splitlines()[0] for s in sections(text)}
    kept = [s.rstrip("\n") + "\n" for s in sections(open(args[1]).read()) if s.splitlines()[0] not in have]
    if kept:
        open(path, "w").write(text.rstrip("\n") + "\n\n" + "\n".join(kept))
    sys.exit(0)
heading = args[0]
section = sys.stdin.read().rstrip("\n") + "\n"
text = open(path).read()
start = text.find(heading)
if start < 0:
    text = text.rstrip("\n") + "\n\n" + section
else:
    end = text.find("\n## ", start + 1)
    text = text[:start] + section + ("" if end < 0 else text[end:])
open(path, "w").write(text)
print(section, end="")
