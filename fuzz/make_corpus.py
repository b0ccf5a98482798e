#!/usr/bin/env python3
"""Regenerate the seed corpora in fuzz/corpus/<target>/. Deterministic; run from anywhere.

mesh_prepare / atlas_bake: soups in the byte layout of FuzzMeshDecode.h (closed cube, tetrahedron, cube with
UVs, inside-out cube, open box, two disjoint cubes, cube inside a cube, raw-double cube with a NaN).
scene_json: the example scenes of bullet_examples/scenes plus a few edge cases.
assimp_import: small allow-listed files from Debian's assimp-testmodels, behind their extension byte.
water_graph_json: the bodies with "water_graph" of bullet_examples/scenes plus hand-made graphs (every key,
  the automatic graph, diffusion, box nodes, permeability regions, a density map).
permeability_image: tiny images in every format stb_image reads (PNG RGB/RGBA/grey, BMP, TGA, PPM, PGM),
  written here byte by byte.
"""
import json, os, shutil, struct, glob, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CORPUS = os.path.join(HERE, "corpus")

CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_T = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
          (3, 7, 6), (3, 6, 2), (0, 4, 7), (0, 7, 3), (1, 2, 6), (1, 6, 5)]
TET_V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TET_T = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def soup(verts, tris, scale=8, uvs=False, raw=False):
    h = (len(verts) - 1) | (0x40 if uvs else 0) | (0x80 if raw else 0)
    out = bytearray([h])
    for v in verts:
        for c in v:
            out += struct.pack("<d", c) if raw else struct.pack("<b", int(round(c * scale)))
    for i, t in enumerate(tris):
        out += bytes(t)
        if uvs:  # each triangle in its own cell of a 4x4 grid: a valid, non-overlapping layout
            cx, cy = (i % 4) * 64, (i // 4) * 64
            out += bytes([cx + 4, cy + 4, cx + 56, cy + 4, cx + 4, cy + 56])
    return bytes(out)


def shifted(verts, d):
    return [(x + d[0], y + d[1], z + d[2]) for x, y, z in verts]


def mesh_seeds():
    two_v = CUBE_V + shifted(CUBE_V, (3, 0, 0))
    two_t = CUBE_T + [tuple(i + 8 for i in t) for t in CUBE_T]
    inner_v = CUBE_V + shifted([(x * 0.5, y * 0.5, z * 0.5) for x, y, z in CUBE_V], (0.25, 0.25, 0.25))
    inner_t = CUBE_T + [tuple(i + 8 for i in reversed(t)) for t in CUBE_T]  # inward: a cavity
    nan_v = list(CUBE_V)
    nan_v[6] = (float("nan"), 1, 1)
    return {
        "cube": soup(CUBE_V, CUBE_T),
        "tetra": soup(TET_V, TET_T),
        "cube_uv": soup(CUBE_V, CUBE_T, uvs=True),
        "cube_inside_out": soup(CUBE_V, [tuple(reversed(t)) for t in CUBE_T]),
        "open_box": soup(CUBE_V, CUBE_T[:-2]),
        "two_cubes": soup(two_v, two_t, scale=4),
        "cavity": soup(inner_v, inner_t, scale=8),
        "cube_raw": soup(CUBE_V, CUBE_T, raw=True),
        "cube_raw_nan": soup(nan_v, CUBE_T, raw=True),
        "tiny_cube": soup(CUBE_V, CUBE_T, scale=1),
    }


def write(target, name, data):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def main():
    for name, data in mesh_seeds().items():
        write("mesh_prepare", name, data)
        write("atlas_bake", name + "_n16", bytes([0, 15]) + data)
        write("atlas_bake", name + "_n64_model_uvs", bytes([1, 63]) + data)
        write("atlas_bake", name + "_n8_texel_centre", bytes([2, 7]) + data)
    for path in sorted(glob.glob(os.path.join(ROOT, "bullet_examples", "scenes", "*.json"))):
        with open(path, "rb") as f:
            write("scene_json", os.path.basename(path), f.read())
    edge = {
        "minimal": {"bodies": []},
        "all_keys": {"gravity": [0, -9.81, 0], "dt": 0.004, "substeps_per_frame": 2, "duration": 1,
                     "output_interval": 0.5, "water": {"type": "flat", "height": 0.5, "density": 1025},
                     "ground": {"height": -3},
                     "bodies": [{"name": "a", "shape": {"type": "cylinder", "radius": 0.3, "height": 1, "resolution": 16},
                                 "mass_model": "shell", "thickness": 0.01, "density": 800, "position": [0, 0, 0],
                                 "rotation": {"axis": [1, 0, 0], "degrees": 90}, "linear_velocity": [0, 1, 0],
                                 "angular_velocity": [0, 0, 1], "collision": "none", "fixed": False,
                                 "ballast": [{"position": [0, -0.4, 0], "mass": 10}],
                                 "buoyancy": {"method": "exact-coverage", "texture": 64, "drag_coefficient": 1,
                                              "skin_friction": 0.01, "linear_damping": 0.3, "radiation_damping": 0.3, "added_mass": True,
                                              "added_mass_coefficient": 0.5,
                                              "added_mass_waterplane_coefficient": 0.2}},
                                {"name": "m", "shape": {"type": "mesh", "file": "x.obj", "scale": 2}, "mass": 3}]},
    }
    for name, scene in edge.items():
        write("scene_json", name + ".json", json.dumps(scene).encode())
    models = "/usr/share/assimp/models"
    exts = [".obj", ".ply", ".stl", ".gltf", ".glb", ".dae", ".fbx", ".3ds"]  # supportedMeshExtensions() order
    picks = ["OBJ/box.obj", "OBJ/concave_polygon.obj", "OBJ/point_cloud.obj", "PLY/cube.ply", "PLY/cube_binary.ply",
             "STL/triangle.stl", "STL/triangle_with_two_solids.stl", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
             "glTF2/TestNoRootNode/NoScene.gltf", "Collada/cube_emptyTags.dae", "Collada/ConcavePolygon.dae",
             "FBX/boxWithUncompressedCTypeArray.FBX", "3DS/RotatingCube.3DS", "invalid/empty.obj"]
    for rel in picks:
        src = os.path.join(models, rel)
        if not os.path.isfile(src):
            continue
        ext = os.path.splitext(rel)[1].lower()
        with open(src, "rb") as f:
            data = f.read()
        write("assimp_import", rel.replace("/", "_"), bytes([exts.index(ext)]) + data)


def graph_seeds():
    seeds = {}
    for path in sorted(glob.glob(os.path.join(ROOT, "bullet_examples", "scenes", "*.json"))):
        with open(path) as f:
            scene = json.load(f)
        for i, body in enumerate(scene.get("bodies", [])):
            keys = {k: body[k] for k in ("water_graph", "permeability", "density_map") if k in body}
            if keys and not isinstance(keys.get("water_graph"), str):
                seeds[os.path.splitext(os.path.basename(path))[0] + "_body%d" % i] = keys
    two = {"nodes": [{"name": "a", "position": [0, -0.2, 0], "capacity": 0.2, "water": 0.05},
                     {"name": "b", "position": [0.3, 0.1, 0], "capacity": 0.1, "size": [0.3, 0.2, 0.4]}],
           "edges": [{"from": "a", "to": "b", "radius": 0.05, "length": 0.4, "permeability": 0.5}]}
    seeds["two_nodes_regions"] = {"water_graph": two, "permeability": {"regions": [
        {"centre": [0.5, 0, 0], "radius": 0.2, "value": 0.3, "node": "b"}, {"centre": [0, -0.5, 0], "radius": 0.1}]}}
    seeds["all_graph_keys"] = {"water_graph": dict(two, seed=7, ingress="paper", flow="diffusion",
                                                   discharge_coefficient=0.8, viscosity=0.002, diffusivity=0.01,
                                                   water_inertia="points"),
                               "permeability": {"regions": [{"centre": [0, 0, 0.5], "radius": 0.3}]}}
    seeds["auto"] = {"water_graph": {"auto": {"nodes": 3, "resolution": 8, "fill": 0.5}, "seed": 3},
                     "permeability": {"regions": [{"centre": [0, -0.5, 0], "radius": 0.3, "value": 1}]}}
    seeds["graph_only"] = two  # the value of "water_graph" alone
    seeds["texture_missing"] = {"water_graph": two, "permeability": {"texture": "holes.png", "filter": "nearest"}}
    seeds["density_map"] = {"water_graph": two, "density_map": {
        "base": 1, "spots": [{"direction": [0, -1, 0], "angle": 30, "value": 5}],
        "rotation": {"axis": [0, 0, 1], "degrees_per_second": 10}, "update_interval": 0.2}}
    return seeds


def png(width, height, colour_type, rows):
    """A PNG with 8-bit samples (colour type 0 grey, 2 RGB, 6 RGBA); rows: list of bytes without filter byte."""
    def chunk(tag, body):
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xffffffff)
    raw = b"".join(b"\x00" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def image_seeds():
    w, h = 4, 3
    rgb = [b"".join(bytes((x * 80 % 256, y * 100, 7)) for x in range(w)) for y in range(h)]
    rgba = [b"".join(bytes((x * 80 % 256, y * 100, 7, 255)) for x in range(w)) for y in range(h)]
    grey = [bytes(x * 60 for x in range(w)) for _ in range(h)]
    bmp_rows = b"".join(b"".join(bytes((7, y * 100, x * 80 % 256)) for x in range(w)) for y in range(h))  # BGR, 12 B/row
    bmp = (b"BM" + struct.pack("<IHHI", 54 + len(bmp_rows), 0, 0, 54) +
           struct.pack("<IiiHHIIiiII", 40, w, h, 1, 24, 0, len(bmp_rows), 2835, 2835, 0, 0) + bmp_rows)
    tga = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, w, h, 24, 0) + bmp_rows
    ppm = b"P6\n%d %d\n255\n" % (w, h) + b"".join(rgb)
    pgm = b"P5\n%d %d\n255\n" % (w, h) + b"".join(grey)
    return {"rgb.png": png(w, h, 2, rgb), "rgba.png": png(w, h, 6, rgba), "grey.png": png(w, h, 0, grey),
            "one_texel.png": png(1, 1, 2, [b"\xff\x00\x00"]), "rgb.bmp": bmp, "rgb.tga": tga, "rgb.ppm": ppm,
            "grey.pgm": pgm, "empty": b""}


def extra_main():
    for name, body in graph_seeds().items():
        write("water_graph_json", name + ".json", json.dumps(body).encode())
    for name, data in image_seeds().items():
        write("permeability_image", name, data)


if __name__ == "__main__":
    main()
    extra_main()
