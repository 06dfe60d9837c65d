#!/usr/bin/env python3
"""Replaces the section of BENCHMARKS-hw.md (or the file given with --file) that starts with the
heading given (its `## ` line's beginning) by the text on standard input, up to the next `## `
heading; appends it when there is none. The bench scripts' one section writer."""
import sys

args = sys.argv[1:]
path = "BENCHMARKS-hw.md"
if args[:1] == ["--file"]:
    path, args = args[1], args[2:]
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
