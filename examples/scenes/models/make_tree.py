#!/usr/bin/env python3
"""Writes tree.gltf, the small tree of docs/scene-format.md's complete example: a trunk (an
eight-sided prism, 3 m) and a crown (a two-tier octagonal cone), two meshes so that each
instance of the model adds two objects. Made for Penumbra, public domain; the buffer is
embedded as a data uri so that the model is one file. Deterministic: rerunning it rewrites
the same bytes.
    python3 examples/scenes/models/make_tree.py
"""
import base64
import json
import math
import os
import struct

SIDES = 8


def ring(radius, y):
    return [(radius * math.cos(2 * math.pi * i / SIDES), y, radius * math.sin(2 * math.pi * i / SIDES))
            for i in range(SIDES)]


def prism(radius, y0, y1):
    """Side walls and top cap of an open-bottomed prism, counter-clockwise seen from outside."""
    positions = ring(radius, y0) + ring(radius, y1) + [(0.0, y1, 0.0)]
    indices = []
    for i in range(SIDES):
        j = (i + 1) % SIDES
        indices += [i, SIDES + i, j, j, SIDES + i, SIDES + j]
        indices += [SIDES + i, 2 * SIDES, SIDES + j]
    return positions, indices


def cone(radius, y0, y1):
    """A cone with its base cap, counter-clockwise seen from outside."""
    positions = ring(radius, y0) + [(0.0, y1, 0.0), (0.0, y0, 0.0)]
    indices = []
    for i in range(SIDES):
        j = (i + 1) % SIDES
        indices += [i, SIDES, j, i, j, SIDES + 1]
    return positions, indices


def merge(parts):
    positions, indices = [], []
    for part_positions, part_indices in parts:
        indices += [len(positions) + k for k in part_indices]
        positions += part_positions
    return positions, indices


def main():
    meshes = [("trunk", prism(0.18, 0.0, 3.0), [0.35, 0.22, 0.12, 1.0]),
              ("crown", merge([cone(1.4, 1.6, 3.6), cone(1.0, 3.0, 4.8)]), [0.18, 0.45, 0.16, 1.0])]
    blob = b""
    document = {"asset": {"version": "2.0", "generator": "Penumbra make_tree.py"},
                "scene": 0, "scenes": [{"nodes": [0, 1]}], "nodes": [], "meshes": [], "materials": [],
                "accessors": [], "bufferViews": []}
    for index, (name, (positions, indices), colour) in enumerate(meshes):
        position_bytes = b"".join(struct.pack("<3f", *p) for p in positions)
        index_bytes = b"".join(struct.pack("<H", i) for i in indices)
        for data, target in ((position_bytes, 34962), (index_bytes, 34963)):
            document["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data),
                                            "target": target})
            blob += data + b"\0" * (-len(data) % 4)
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        document["accessors"].append({"bufferView": 2 * index, "componentType": 5126, "count": len(positions),
                                      "type": "VEC3", "min": lo, "max": hi})
        document["accessors"].append({"bufferView": 2 * index + 1, "componentType": 5123, "count": len(indices),
                                      "type": "SCALAR"})
        document["materials"].append({"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": colour, "metallicFactor": 0.0, "roughnessFactor": 0.9}})
        document["meshes"].append({"name": name, "primitives": [
            {"attributes": {"POSITION": 2 * index}, "indices": 2 * index + 1, "material": index}]})
        document["nodes"].append({"name": name, "mesh": index})
    document["buffers"] = [{"byteLength": len(blob),
                            "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "tree.gltf")
    with open(path, "w") as file:
        json.dump(document, file, indent=1)
        file.write("\n")


if __name__ == "__main__":
    main()
