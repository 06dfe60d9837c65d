"""A step of scripts/bench_prove.sh (its arguments as there: sys.argv[1:])."""
import os, sys
p, buf = sys.argv[1], sys.argv[2]
if os.environ.get("DELETE"):
    s = open(buf).read(); a = s.rfind("`ifdef FORMAL"); b = a + s[a:].find("`endif") + len("`endif")
    open(buf, "w").write(s[:a] + s[b:])
if os.environ.get("NEUTER"):
    # every assertion of the unit's kept in number and made empty: its lemmas say nothing
    for f in (p, buf, os.path.join(os.path.dirname(p), "specular_unit.v")):
        t = open(f).read()
        if "assert(1'b1 || " not in t:
            open(f, "w").write(t.replace("assert(", "assert(1'b1 || "))
s = open(p).read(); a, b = os.environ["FROM"], os.environ["TO"]
assert s.count(a) == 1, a
open(p, "w").write(s.replace(a, b))
