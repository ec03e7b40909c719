#!/usr/bin/env python3
"""Prints the docs/performance.md table from the medians criterion saved under target/criterion.

Run after `cargo bench -p condt-compare --bench triangulate`:
`python3 scripts/criterion_table.py [CRITERION_DIR]` (default: the workspace's target/criterion).
"""
import json, os, sys
root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "target", "criterion")
groups = ["uniform_10k", "uniform_100k", "uniform_1M", "ellipses_1M", "clustered_1M", "grid_1M", "uniform_offset_1e6_1M"]
def med(g, b):
    p = os.path.join(root, g, b, "new", "estimates.json")
    if not os.path.exists(p): return None
    return json.load(open(p))["median"]["point_estimate"] / 1e6  # ms
def fmt(ms):
    return "—" if ms is None else (f"{ms/1000:.2f} s" if ms >= 1000 else f"{ms:.1f} ms" if ms >= 10 else f"{ms:.2f} ms")
print("| input | condt | condt, 2 threads | spade `bulk_load` | delaunator | Hilbert sort | condt / spade | condt / delaunator | condt / sort |")
print("|---|---|---|---|---|---|---|---|---|")
for g in groups:
    c, p, s, d, h = (med(g, b) for b in ("condt", "condt_parallel", "spade_bulk_load", "delaunator", "hilbert_sort"))
    r = lambda a, b: "—" if a is None or b is None else f"{a/b:.3f}"
    print(f"| {g} | {fmt(c)} | {fmt(p)} | {fmt(s)} | {fmt(d)} | {fmt(h)} | {r(c,s)} | {r(c,d)} | {r(c,h)} |")
