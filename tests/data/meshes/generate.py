#!/usr/bin/env python3
"""Writes the small broken (and a few good) meshes used by tests/mesh/. Run from this folder:
    python3 generate.py
Every file is built from the unit-cube corners below, so the tests can state the expected counts by hand.
"""
import base64, json, struct

# Cube [0,1]^3: corner k has bits (x, y, z) = (k & 1, k >> 1 & 1, k >> 2 & 1).
CORNERS = [((k & 1), (k >> 1) & 1, (k >> 2) & 1) for k in range(8)]
# Outward, counter-clockwise quads (0-based corner indices), each split along its first diagonal.
QUADS = [(0, 2, 3, 1),  # z = 0 (normal -z)
         (4, 5, 7, 6),  # z = 1
         (0, 1, 5, 4),  # y = 0
         (2, 6, 7, 3),  # y = 1
         (0, 4, 6, 2),  # x = 0
         (1, 3, 7, 5)]  # x = 1


def cube_tris(offset=0):
    out = []
    for a, b, c, d in QUADS:
        out += [(a + offset, b + offset, c + offset), (a + offset, c + offset, d + offset)]
    return out


def write_obj(name, verts, tris, comment):
    with open(name, "w") as f:
        f.write("# %s (written by generate.py)\n" % comment)
        for v in verts:
            f.write("v %s %s %s\n" % tuple(v))
        for t in tris:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def box(lo, hi):
    return [tuple(lo[i] + (hi[i] - lo[i]) * c[i] for i in range(3)) for c in CORNERS]


unit = box((0, 0, 0), (1, 1, 1))
tris = cube_tris()

# open: the z = 1 face (triangles 2, 3) removed -> its 4 outer edges are boundary edges.
write_obj("open_box.obj", unit, tris[:2] + tris[4:], "unit cube without its z=1 face: 4 boundary edges")

# non-manifold: two cubes sharing only the edge x = 1, y = 1 (0 <= z <= 1) -> that edge has 4 faces.
b2 = box((1, 1, 0), (2, 2, 1))
write_obj("nonmanifold_edge.obj", unit + b2, tris + cube_tris(8),
          "two unit cubes sharing one edge: 1 edge shared by 4 faces")

# inverted: every triangle reversed.
write_obj("inverted_box.obj", unit, [(a, c, b) for a, b, c in tris], "unit cube, all triangles inward")

# flipped patch: the x = 1 face (triangles 10, 11) reversed -> its 4 outer edges run the same way twice.
fp = list(tris)
fp[10] = (fp[10][0], fp[10][2], fp[10][1])
fp[11] = (fp[11][0], fp[11][2], fp[11][1])
write_obj("flipped_patch.obj", unit, fp, "unit cube with its x=1 face reversed: 4 inconsistent edges")

# NaN vertex.
nanv = [list(v) for v in unit]
nanv[7] = ["nan", 1, 1]
write_obj("nan_vertex.obj", nanv, tris, "unit cube with one NaN coordinate")

# zero-area: unit cube + (a) a triangle with a repeated corner, (b) two collinear triangles on the edge
# from corner 0 to corner 1 through the extra midpoint vertex 8. All three must be removed.
za = unit + [(0.5, 0, 0)]
write_obj("zero_area.obj", za, tris + [(0, 0, 1), (0, 8, 1), (0, 1, 8)],
          "unit cube + 3 zero-area triangles (1 repeated corner, 2 collinear)")

# huge coordinates (float-representable, beyond the 1e6 m limit).
write_obj("huge_coordinates.obj", box((0, 0, 0), (1e30, 1e30, 1e30)), tris, "cube of side 1e30")

# cavity: outer box [0,4]^3 outward, inner box [1,3]^3 inward -> V = 64 - 8 = 56.
inner = box((1, 1, 1), (3, 3, 3))
write_obj("box_with_cavity.obj", box((0, 0, 0), (4, 4, 4)) + inner,
          tris + [(a, c, b) for a, b, c in cube_tris(8)], "box 4^3 with a 2^3 cavity (inner box inward)")

# two outward boxes that intersect: [0,2]^3 and [1,3]^3.
write_obj("intersecting_boxes.obj", box((0, 0, 0), (2, 2, 2)) + box((1, 1, 1), (3, 3, 3)),
          tris + cube_tris(8), "two overlapping boxes")

# empty file and an unknown extension.
open("empty.obj", "w").close()
write_obj("box.xyz", unit, tris, "a good cube with an extension off the allow-list")

# STL triangle soup of the box [1,2] x [-1,1] x [0,3] (a x b x c = 1 x 2 x 3): 12 facets, 36 corners.
sb = box((1, -1, 0), (2, 1, 3))
with open("box_soup.stl", "w") as f:
    f.write("solid box\n")
    for t in tris:
        f.write("  facet normal 0 0 0\n    outer loop\n")
        for i in t:
            f.write("      vertex %g %g %g\n" % sb[i])
        f.write("    endloop\n  endfacet\n")
    f.write("endsolid box\n")

# glTF 2.0 with node transforms: one mesh (cube centred on the origin, side 1) instanced twice:
#   node 0 (translation [10,0,0]) -> child node 1 (scale [2,3,4]) with the mesh: box 2x3x4 at (10,0,0)
#   node 2 (scale [-1,1,1], translation [0,-20,0]) with the mesh: a mirrored unit cube at (0,-20,0)
centred = [tuple(c - 0.5 for c in v) for v in unit]
pos = b"".join(struct.pack("<3f", *v) for v in centred)
idx = b"".join(struct.pack("<3H", *t) for t in tris)
buf = pos + idx
gltf = {
    "asset": {"version": "2.0", "generator": "generate.py"},
    "scene": 0,
    "scenes": [{"nodes": [0, 2]}],
    "nodes": [{"translation": [10, 0, 0], "children": [1]},
              {"scale": [2, 3, 4], "mesh": 0},
              {"scale": [-1, 1, 1], "translation": [0, -20, 0], "mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
    "buffers": [{"byteLength": len(buf),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
                    {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx), "target": 34963}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                   "min": [-0.5, -0.5, -0.5], "max": [0.5, 0.5, 0.5]},
                  {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
}
with open("node_transforms.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
