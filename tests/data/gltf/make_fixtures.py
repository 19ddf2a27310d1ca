#!/usr/bin/env python3
"""Writes the small glTF fixtures used by tests/unit/test_gltf_*.cpp.

Run from anywhere: python3 tests/data/gltf/make_fixtures.py. The outputs are committed;
rerun after changing this script. Every model is built from a unit quad in XZ facing +Y
(counter-clockwise seen from above) so the tests can predict counts, normals and bounds.
"""
import base64
import copy
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125

# Quad corners: counter-clockwise seen from +Y.
POSITIONS = [(-0.5, 0.0, 0.5), (0.5, 0.0, 0.5), (0.5, 0.0, -0.5), (-0.5, 0.0, -0.5)]
NORMALS = [(0.0, 1.0, 0.0)] * 4
UVS = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
INDICES = [0, 1, 2, 0, 2, 3]


def pad4(data):
    return data + b"\0" * (-len(data) % 4)


def pack(fmt, rows):
    return b"".join(struct.pack(fmt, *row) for row in rows)


def index_bytes(indices, component_type):
    fmt = {UBYTE: "<B", USHORT: "<H", UINT: "<I"}[component_type]
    return pad4(b"".join(struct.pack(fmt, i) for i in indices))


class Builder:
    """Accumulates one buffer plus its views and accessors."""

    def __init__(self):
        self.data = b""
        self.views = []
        self.accessors = []

    def add(self, payload, component_type, type_name, count, normalized=False):
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)})
        self.data += pad4(payload)
        accessor = {"bufferView": len(self.views) - 1, "componentType": component_type, "count": count,
                    "type": type_name}
        if normalized:
            accessor["normalized"] = True
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def quad_document(index_type=USHORT, with_normals=True, with_indices=True, positions=POSITIONS,
                  indices=INDICES, mode=None):
    builder = Builder()
    attributes = {"POSITION": builder.add(pack("<3f", positions), FLOAT, "VEC3", len(positions))}
    if with_normals:
        attributes["NORMAL"] = builder.add(pack("<3f", NORMALS[:1] * len(positions)), FLOAT, "VEC3", len(positions))
    attributes["TEXCOORD_0"] = builder.add(pack("<2f", (UVS * 3)[:len(positions)]), FLOAT, "VEC2", len(positions))
    primitive = {"attributes": attributes, "material": 0}
    if with_indices:
        primitive["indices"] = builder.add(index_bytes(indices, index_type), index_type, "SCALAR", len(indices))
    if mode is not None:
        primitive["mode"] = mode
    return {
        "asset": {"version": "2.0", "generator": "penumbra make_fixtures.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [1.0, 2.0, 3.0]}],
        "meshes": [{"primitives": [primitive]}],
        "materials": [{
            "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1.0, 0.8], "roughnessFactor": 0.4,
                                     "metallicFactor": 0.1},
            "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": True}],
        "buffers": [{"byteLength": len(builder.data)}],
        "bufferViews": builder.views,
        "accessors": builder.accessors,
    }, builder.data


def embed(document, data):
    document = copy.deepcopy(document)
    document["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    return document


def write_json(name, document):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(document, f, indent=1)
        f.write("\n")


def write_bytes(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def glb(document, data):
    json_chunk = json.dumps(document).encode()
    json_chunk += b" " * (-len(json_chunk) % 4)
    data = pad4(data)
    body = struct.pack("<I4s", len(json_chunk), b"JSON") + json_chunk + struct.pack("<I4s", len(data), b"BIN\0") + data
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def png(width, height, channels, rows, bit_depth=8):
    """Minimal PNG writer: colour type 0/4/2/6 for 1/2/3/4 channels."""
    color_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    fmt = ">H" if bit_depth == 16 else ">B"
    raw = b"".join(b"\0" + b"".join(struct.pack(fmt, v) for v in row) for row in rows)

    def chunk(kind, payload):
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))

    header = struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def textured(document, png_bytes):
    document = copy.deepcopy(document)
    document["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode()}]
    document["textures"] = [{"source": 0}]
    document["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    return document


def write_valid_fixtures():
    document, data = quad_document()
    write_json("quad.gltf", embed(document, data))
    external = copy.deepcopy(document)
    external["buffers"][0]["uri"] = "quad.bin"
    write_json("quad_external.gltf", external)
    write_bytes("quad.bin", data)
    write_bytes("quad.glb", glb(document, data))

    for name, index_type in (("quad_u8.gltf", UBYTE), ("quad_u32.gltf", UINT)):
        write_json(name, embed(*quad_document(index_type=index_type)))

    # Six vertices, no indices, no normals: the loader must generate both.
    six = [POSITIONS[i] for i in INDICES]
    write_json("unindexed_no_normals.gltf", embed(*quad_document(with_normals=False, with_indices=False,
                                                                  positions=six)))
    # Strip 0,1,3,2 and fan 0,1,2,3 both cover the quad with two triangles.
    write_json("strip.gltf", embed(*quad_document(indices=[0, 1, 3, 2], mode=5)))
    write_json("fan.gltf", embed(*quad_document(indices=[0, 1, 2, 3], mode=6)))

    # Points and lines cast no shadow and are skipped; the triangles remain.
    document, data = quad_document()
    triangles = document["meshes"][0]["primitives"][0]
    points = dict(triangles, mode=0)
    lines = dict(triangles, mode=1)
    document["meshes"][0]["primitives"] = [points, triangles, lines]
    write_json("points_lines_triangles.gltf", embed(document, data))

    # Hierarchy: parent moves +10 X; child 1 scales by 2 through a matrix; child 2 mirrors X.
    # Node 3 is not in the scene and must not be placed.
    document, data = quad_document()
    document["scenes"] = [{"nodes": [0]}]
    document["nodes"] = [
        {"translation": [10.0, 0.0, 0.0], "children": [1, 2]},
        {"mesh": 0, "matrix": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 5, 0, 1]},
        {"mesh": 0, "scale": [-1.0, 1.0, 1.0], "rotation": [0.0, 0.0, 0.0, 1.0]},
        {"mesh": 0, "translation": [100.0, 0.0, 0.0]},
    ]
    write_json("hierarchy.gltf", embed(document, data))
    # Without scenes every root node is placed.
    no_scene = copy.deepcopy(document)
    del no_scene["scenes"]
    del no_scene["scene"]
    write_json("no_scene.gltf", embed(no_scene, data))

    document, data = quad_document()
    rgba = [[255, 0, 0, 255, 0, 255, 0, 128], [0, 0, 255, 0, 255, 255, 255, 255]]
    write_json("textured.gltf", textured(embed(document, data), png(2, 2, 4, rgba)))
    grey_alpha_16 = [[0xFFFF, 0x8000, 0x1234, 0x0000], [0x0000, 0xFFFF, 0x8080, 0x4000]]
    write_json("textured_grey_alpha16.gltf", textured(embed(document, data), png(2, 2, 2, grey_alpha_16, 16)))


def write_malformed_fixtures():
    document, data = quad_document()
    write_bytes("malformed.gltf", b'{"asset": {"version": "2.0"}, "meshes": [ {"primitives": ')
    whole = glb(document, data)
    write_bytes("truncated.glb", whole[: len(whole) // 2])

    truncated = copy.deepcopy(document)
    truncated["buffers"][0]["uri"] = "truncated.bin"
    write_json("truncated_buffer.gltf", truncated)
    write_bytes("truncated.bin", data[: len(data) // 2])

    missing = copy.deepcopy(document)
    missing["buffers"][0]["uri"] = "does_not_exist.bin"
    write_json("missing_buffer.gltf", missing)

    def variant(name, mutate):
        mutated = embed(document, data)
        mutate(mutated)
        write_json(name, mutated)

    variant("accessor_out_of_range.gltf", lambda d: d["accessors"][0].update(count=1000))
    variant("accessor_offset_out_of_range.gltf", lambda d: d["accessors"][1].update(byteOffset=40))
    variant("buffer_view_out_of_range.gltf", lambda d: d["bufferViews"][3].update(byteLength=4096))
    variant("missing_accessor.gltf",
            lambda d: d["meshes"][0]["primitives"][0]["attributes"].update(POSITION=42))
    variant("no_position.gltf", lambda d: d["meshes"][0]["primitives"][0]["attributes"].pop("POSITION"))
    variant("wrong_position_type.gltf", lambda d: d["accessors"][0].update(componentType=USHORT))
    variant("unknown_mode.gltf", lambda d: d["meshes"][0]["primitives"][0].update(mode=9))
    # glTF requires the nodes to form disjoint strict trees; each way of breaking that.
    variant("node_cycle.gltf", lambda d: d["nodes"].extend([{"children": [2]}, {"children": [1]}]))
    variant("node_two_parents.gltf", lambda d: d["nodes"].extend([{"children": [2]}, {"mesh": 0}])
            or d["nodes"][0].update(children=[2]))
    variant("node_listed_twice.gltf", lambda d: d["nodes"].append({"mesh": 0})
            or d["nodes"][0].update(children=[1, 1]))
    variant("node_own_child.gltf", lambda d: d["nodes"][0].update(children=[0]))
    variant("root_listed_twice.gltf", lambda d: d["scenes"][0].update(nodes=[0, 0]))
    variant("root_with_parent.gltf", lambda d: d["nodes"].append({"mesh": 0})
            or d["nodes"][0].update(children=[1]) or d["scenes"][0].update(nodes=[0, 1]))
    # Values of the wrong JSON type or sign, which tinygltf would skip or misread.
    variant("byte_stride_negative.gltf", lambda d: d["bufferViews"][0].update(byteStride=-4))
    variant("mesh_not_an_index.gltf", lambda d: d["nodes"][0].update(mesh="zero"))
    variant("scene_not_an_index.gltf", lambda d: d.update(scene="hello"))
    variant("missing_material.gltf", lambda d: d["meshes"][0]["primitives"][0].update(material=5))
    variant("bad_alpha_mode.gltf", lambda d: d["materials"][0].update(alphaMode="CUTOUT"))
    variant("partial_triangle.gltf", lambda d: d["accessors"][3].update(count=5))

    bad_index = embed(*quad_document(indices=[0, 1, 2, 0, 2, 7]))
    write_json("index_out_of_range.gltf", bad_index)

    # The first node's mesh loads, the second's does not: a failed load must not leave the first.
    def second_mesh_broken(d):
        broken = copy.deepcopy(d["meshes"][0])
        broken["primitives"][0]["material"] = 5
        d["meshes"].append(broken)
        d["nodes"].append({"mesh": 1})
        d["scenes"][0]["nodes"].append(1)

    variant("second_mesh_broken.gltf", second_mesh_broken)

    missing_image = textured(embed(document, data), b"")
    missing_image["images"] = [{"uri": "missing.png"}]
    write_json("missing_image.gltf", missing_image)


if __name__ == "__main__":
    write_valid_fixtures()
    write_malformed_fixtures()
