#!/usr/bin/env python3
"""Write bullet_examples/scenes/fft_fleet.json: 200 mixed bodies (boxes, balls, logs, boats) in an FFT ocean.

The bodies are primitives made by the library (box, sphere, cylinder) and the boat hull of
bullet_examples/models/boat_hull.obj; positions, sizes and densities come from a fixed seed, so the file
is reproducible: python3 scripts/make_fleet_scene.py
"""
import json
import math
import os
import random

rng = random.Random(8)
bodies = []
n_side = 15                     # 15 x 15 grid slots, the first 200 used
spacing = 3.2                   # m
kinds = ["box"] * 7 + ["sphere"] * 6 + ["log"] * 5 + ["boat"] * 2
for k in range(200):
    i, j = k % n_side, k // n_side
    x = (i - (n_side - 1) / 2) * spacing + rng.uniform(-0.6, 0.6)
    z = (j - (n_side - 1) / 2) * spacing + rng.uniform(-0.6, 0.6)
    kind = kinds[k % len(kinds)]
    body = {"name": f"{kind}{k}", "position": [round(x, 3), 0.3, round(z, 3)],
            "rotation": {"axis": [0, 1, 0], "degrees": round(rng.uniform(0, 360), 1)}}
    if kind == "box":
        body["shape"] = {"type": "box", "size": [round(rng.uniform(0.4, 1.2), 2), round(rng.uniform(0.3, 0.7), 2),
                                                 round(rng.uniform(0.4, 1.2), 2)]}
        body["density"] = round(rng.uniform(300, 800))
    elif kind == "sphere":
        body["shape"] = {"type": "sphere", "radius": round(rng.uniform(0.25, 0.5), 2), "resolution": 16}
        body["density"] = round(rng.uniform(200, 700))
    elif kind == "log":
        body["shape"] = {"type": "cylinder", "radius": round(rng.uniform(0.12, 0.25), 2),
                         "height": round(rng.uniform(1.2, 2.4), 2), "resolution": 12}
        body["density"] = round(rng.uniform(450, 800))
        a = rng.uniform(0, 2 * math.pi)  # lying down: axis y turned into the horizontal direction a
        body["rotation"] = {"axis": [round(math.cos(a), 4), 0, round(math.sin(a), 4)], "degrees": 90}
    else:
        body["shape"] = {"type": "mesh", "file": "../models/boat_hull.obj", "scale": 0.6}
        body["density"] = 300
    bodies.append(body)

scene = {
    "duration": 20,
    "dt": 1 / 120,              # 120 Hz, 2 substeps a frame: 200 bodies stay interactive in the browser
    "substeps_per_frame": 2,
    "output_interval": 0.1,
    "water": {"type": "fft", "height": 0, "resolution": 64, "patch_size": 64, "wind_speed": 9,
              "wind_direction": [1, 0.4], "spectrum": "phillips", "choppiness": 0.4, "seed": 3},
    "camera": {"target": [0, 0, 0], "distance": 38, "yaw": 30, "pitch": 32},
    "bodies": bodies,
}
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bullet_examples", "scenes", "fft_fleet.json")
with open(out, "w") as f:
    f.write("{\n")
    keys = [k for k in scene if k != "bodies"]
    for k in keys:
        f.write(f'  "{k}": {json.dumps(scene[k])},\n')
    f.write('  "bodies": [\n')
    f.write(",\n".join("    " + json.dumps(b) for b in bodies))
    f.write("\n  ]\n}\n")
print("wrote", os.path.normpath(out), len(bodies), "bodies")
