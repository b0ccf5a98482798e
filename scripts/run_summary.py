#!/usr/bin/env python3
"""Print a short per-body summary of a `buoyancy run` output folder (DIR/trajectory.csv):
final position, min/max heave (COM y) and its amplitude, mean submerged volume.
Usage: python3 scripts/run_summary.py DIR"""
import csv, os, sys

if len(sys.argv) != 2:
    print(__doc__)
    sys.exit(2)
path = os.path.join(sys.argv[1], "trajectory.csv")
bodies = {}
with open(path) as f:
    for row in csv.DictReader(f):
        bodies.setdefault(row["body"], []).append(row)
print(f"{'body':<12} {'final position (x, y, z) m':<30} {'heave min..max m':<20} {'amplitude m':>11} {'mean V_sub m3':>14}")
for name, rows in bodies.items():
    last = rows[-1]
    ys = [float(r["cy"]) for r in rows]
    v = [float(r["submerged_volume"]) for r in rows]
    pos = "(%.2f, %.2f, %.2f)" % (float(last["x"]), float(last["y"]), float(last["z"]))
    print(f"{name:<12} {pos:<30} {'%.3f .. %.3f' % (min(ys), max(ys)):<20} {(max(ys) - min(ys)) / 2:>11.3f} {sum(v) / len(v):>14.4f}")
print(f"({len(next(iter(bodies.values())))} rows per body, t = 0 .. {float(last['t']):.1f} s)")
