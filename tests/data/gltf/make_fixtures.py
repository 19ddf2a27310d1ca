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

BYTE, UBYTE, SHORT, USHORT, UINT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126

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


def extend(document, data):
    """A Builder that appends to an existing document's buffer, views and accessors."""
    builder = Builder()
    builder.data, builder.views, builder.accessors = data, document["bufferViews"], document["accessors"]
    return builder


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


def write_conformance_fixtures():
    """glTF features each equivalent to a plain fixture (issue 19): loaded, they give the
    same world-space quad, normals, texture coordinates and indices as quad.gltf or
    textured.gltf."""
    # Sparse positions: the dense data has vertices 1 and 2 wrong; the sparse part restores them.
    document, data = quad_document()
    builder = extend(document, data)
    wrong = [POSITIONS[0], (9.0, 9.0, 9.0), (9.0, 9.0, 9.0), POSITIONS[3]]
    dense = builder.add(pack("<3f", wrong), FLOAT, "VEC3", 4)
    sparse_indices = builder.add(pack("<H", [(1,), (2,)]), USHORT, "SCALAR", 2)
    sparse_values = builder.add(pack("<3f", POSITIONS[1:3]), FLOAT, "VEC3", 2)
    accessor = document["accessors"][dense]
    accessor["sparse"] = {"count": 2,
                          "indices": {"bufferView": document["accessors"][sparse_indices]["bufferView"],
                                      "componentType": USHORT},
                          "values": {"bufferView": document["accessors"][sparse_values]["bufferView"]}}
    document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = dense
    # Sparse indices too: the dense triangle list reads 0,1,2,0,0,0; the sparse part sets 2,3.
    index_dense = builder.add(index_bytes([0, 1, 2, 0, 0, 0], USHORT), USHORT, "SCALAR", 6)
    index_positions = builder.add(pack("<B", [(4,), (5,)]), UBYTE, "SCALAR", 2)
    index_values = builder.add(pack("<H", [(2,), (3,)]), USHORT, "SCALAR", 2)
    document["accessors"][index_dense]["sparse"] = {
        "count": 2,
        "indices": {"bufferView": document["accessors"][index_positions]["bufferView"], "componentType": UBYTE},
        "values": {"bufferView": document["accessors"][index_values]["bufferView"]}}
    document["meshes"][0]["primitives"][0]["indices"] = index_dense
    document["buffers"][0]["byteLength"] = len(builder.data)
    write_json("sparse.gltf", embed(document, builder.data))

    # A sparse accessor without a bufferView starts as zeros: every vertex substituted.
    document, data = quad_document()
    builder = extend(document, data)
    all_indices = builder.add(pack("<B", [(0,), (1,), (2,), (3,)]), UBYTE, "SCALAR", 4)
    all_values = builder.add(pack("<3f", POSITIONS), FLOAT, "VEC3", 4)
    document["accessors"].append({"componentType": FLOAT, "count": 4, "type": "VEC3", "sparse": {
        "count": 4,
        "indices": {"bufferView": document["accessors"][all_indices]["bufferView"], "componentType": UBYTE},
        "values": {"bufferView": document["accessors"][all_values]["bufferView"]}}})
    document["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = len(document["accessors"]) - 1
    document["buffers"][0]["byteLength"] = len(builder.data)
    write_json("sparse_without_buffer_view.gltf", embed(document, builder.data))

    # The alpha texture reads TEXCOORD_1; TEXCOORD_0 is all zeros.
    document, data = quad_document()
    builder = extend(document, data)
    attributes = document["meshes"][0]["primitives"][0]["attributes"]
    attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"]
    attributes["TEXCOORD_0"] = builder.add(pack("<2f", [(0.0, 0.0)] * 4), FLOAT, "VEC2", 4)
    document["buffers"][0]["byteLength"] = len(builder.data)
    rgba = [[255, 0, 0, 255, 0, 255, 0, 128], [0, 0, 255, 0, 255, 255, 255, 255]]
    second_set = textured(embed(document, builder.data), png(2, 2, 4, rgba))
    second_set["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1
    write_json("texcoord1.gltf", second_set)

    # Morph targets: the base quad sits 1 m higher; one target moves it down by 1 m and tilts
    # its normals, weighted 1 by the mesh (morph_mesh_weights) or by the node over a mesh
    # weight of 0 (morph_node_weights). A second target with weight 0 would move it away.
    for name, mesh_weights, node_weights in (("morph_mesh_weights.gltf", [1.0, 0.0], None),
                                             ("morph_node_weights.gltf", [0.0, 0.0], [1.0, 0.0])):
        document, data = quad_document()
        builder = extend(document, data)
        raised = [(x, y + 1.0, z) for x, y, z in POSITIONS]
        primitive = document["meshes"][0]["primitives"][0]
        primitive["attributes"]["POSITION"] = builder.add(pack("<3f", raised), FLOAT, "VEC3", 4)
        primitive["attributes"]["NORMAL"] = builder.add(pack("<3f", [(1.0, 1.0, 0.0)] * 4), FLOAT, "VEC3", 4)
        down = builder.add(pack("<3f", [(0.0, -1.0, 0.0)] * 4), FLOAT, "VEC3", 4)
        untilt = builder.add(pack("<3f", [(-1.0, 0.0, 0.0)] * 4), FLOAT, "VEC3", 4)
        away = builder.add(pack("<3f", [(50.0, 0.0, 0.0)] * 4), FLOAT, "VEC3", 4)
        primitive["targets"] = [{"POSITION": down, "NORMAL": untilt}, {"POSITION": away}]
        document["meshes"][0]["weights"] = mesh_weights
        if node_weights is not None:
            document["nodes"][0]["weights"] = node_weights
        document["buffers"][0]["byteLength"] = len(builder.data)
        write_json(name, embed(document, builder.data))

    # KHR_mesh_quantization: positions as SHORT twice the size, halved by the node's scale;
    # normals as normalized BYTE; texture coordinates as UNSIGNED_BYTE (not normalized).
    document, data = quad_document()
    builder = extend(document, data)
    attributes = document["meshes"][0]["primitives"][0]["attributes"]
    doubled = [tuple(int(2 * c) for c in p) for p in POSITIONS]
    attributes["POSITION"] = builder.add(pad4(pack("<3h", doubled)), SHORT, "VEC3", 4)
    builder.views[-1]["byteStride"] = 8  # vertex attributes are 4-byte aligned
    builder.views[-1]["byteLength"] = 32
    builder.data = builder.data[:builder.views[-1]["byteOffset"]] + b"".join(
        struct.pack("<3hxx", *p) for p in doubled)
    attributes["NORMAL"] = builder.add(pack("<3bx", [(0, 127, 0)] * 4), BYTE, "VEC3", 4, normalized=True)
    builder.views[-1]["byteStride"] = 4
    attributes["TEXCOORD_0"] = builder.add(pack("<2Bxx", [(int(u), int(v)) for u, v in UVS]), UBYTE, "VEC2", 4)
    builder.views[-1]["byteStride"] = 4
    document["nodes"][0]["scale"] = [0.5, 0.5, 0.5]
    document["extensionsUsed"] = ["KHR_mesh_quantization"]
    document["extensionsRequired"] = ["KHR_mesh_quantization"]
    document["buffers"][0]["byteLength"] = len(builder.data)
    write_json("quantized.gltf", embed(document, builder.data))
    undeclared = embed(document, builder.data)
    del undeclared["extensionsUsed"], undeclared["extensionsRequired"]
    write_json("quantized_undeclared.gltf", undeclared)

    # Samplers on alpha masks: a quad whose u runs 0..2 over a 2x1 nearest-filtered mask
    # [opaque, clear] reads, past u = 1, the clear texel again (clamp) or the row mirrored
    # (mirrored repeat); each equals a quad with u in 0..1 over the 4x1 mask it amounts to,
    # read with repeat: [opaque, clear, clear, clear] and [opaque, clear, clear, opaque].
    wide_uvs = [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]
    for name, wrap, expanded in (("alpha_clamped", 33071, [255, 0, 0, 0]),
                                 ("alpha_mirrored", 33648, [255, 0, 0, 255])):
        for suffix, uvs, alphas, wrap_s in (("", wide_uvs, [255, 0], wrap), ("_expanded", UVS, expanded, 10497)):
            document, data = quad_document()
            builder = extend(document, data)
            document["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = builder.add(
                pack("<2f", uvs), FLOAT, "VEC2", 4)
            document["buffers"][0]["byteLength"] = len(builder.data)
            row = [channel for alpha in alphas for channel in (255, 255, 255, alpha)]
            masked = textured(embed(document, builder.data), png(len(alphas), 1, 4, [row]))
            masked["samplers"] = [{"magFilter": 9728, "minFilter": 9728, "wrapS": wrap_s, "wrapT": 33071}]
            masked["textures"][0]["sampler"] = 0
            masked["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = [1.0, 1.0, 1.0, 1.0]
            masked["materials"][0]["alphaCutoff"] = 0.5
            write_json(name + suffix + ".gltf", masked)

    # A striped BLEND caster like the coating of Khronos' ClearCoatTest (issue 16, item 2):
    # an alpha ramp repeated twice across the quad (UVs 0..2, REPEAT) and shifted a quarter
    # by KHR_texture_transform, nearest filtering; BLEND casts as MASK at 0.5, so
    # blend_striped_mask.gltf (MASK, cutoff 0.5) must cast exactly the same shadow.
    for name, mode in (("blend_striped", "BLEND"), ("blend_striped_mask", "MASK")):
        document, data = quad_document()
        builder = extend(document, data)
        document["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = builder.add(
            pack("<2f", [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]), FLOAT, "VEC2", 4)
        document["buffers"][0]["byteLength"] = len(builder.data)
        ramp = [0, 64, 127, 128, 200, 255, 200, 64]
        row = [channel for alpha in ramp for channel in (0, 0, 0, alpha)]
        striped = textured(embed(document, builder.data), png(len(ramp), 1, 4, [row]))
        striped["samplers"] = [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 33071}]
        striped["textures"][0]["sampler"] = 0
        material = striped["materials"][0]
        material["pbrMetallicRoughness"]["baseColorFactor"] = [1.0, 1.0, 1.0, 1.0]
        material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
            "KHR_texture_transform": {"offset": [0.25, 0.0]}}
        material["alphaMode"] = mode
        material["alphaCutoff"] = 0.5
        if mode == "BLEND":
            del material["alphaCutoff"]
        striped["extensionsUsed"] = ["KHR_texture_transform"]
        write_json(name + ".gltf", striped)

    # KHR_lights_punctual: a spot 5 m above the quad's node shining down (-Z turned to -Y by
    # -90 degrees about X), a point light without a range, and a directional light tilted
    # down; the quad is node 0.
    document, data = quad_document()
    down = [-0.7071067811865476, 0.0, 0.0, 0.7071067811865476]
    document["nodes"] += [
        {"translation": [0.0, 5.0, 0.0], "rotation": down, "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"translation": [2.0, 3.0, 0.0], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"rotation": down, "extensions": {"KHR_lights_punctual": {"light": 2}}},
    ]
    document["scenes"][0]["nodes"] = [0, 1, 2, 3]
    document["extensionsUsed"] = ["KHR_lights_punctual"]
    document["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1.0, 0.5, 0.25], "intensity": 40.0, "range": 12.0,
         "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
        {"type": "point", "intensity": 4.0},
        {"type": "directional", "intensity": 2.5},
    ]}}
    write_json("lights.gltf", embed(document, data))

    # Names for exclude_casters: node "ground" places mesh "floor", node "sky dome" places
    # mesh "sky_mesh"; node "backdrop" places mesh "card" whose material is unlit.
    document, data = quad_document()
    primitive = document["meshes"][0]["primitives"][0]
    document["meshes"] = [{"name": "floor", "primitives": [primitive]},
                          {"name": "sky_mesh", "primitives": [primitive]},
                          {"name": "card", "primitives": [dict(primitive, material=1)]}]
    document["materials"].append({"extensions": {"KHR_materials_unlit": {}}})
    document["extensionsUsed"] = ["KHR_materials_unlit"]
    document["nodes"] = [{"name": "ground", "mesh": 0}, {"name": "sky dome", "mesh": 1},
                         {"name": "backdrop", "mesh": 2}]
    document["scenes"][0]["nodes"] = [0, 1, 2]
    write_json("named.gltf", embed(document, data))

    # KHR_texture_transform on the alpha texture: UVs stored as 2 uv - 1 come back to uv under
    # scale 0.5 and offset 0.5; UVs stored rotated come back under the rotation (0.5 rad about
    # the origin, u' = cos u + sin v, v' = -sin u + cos v).
    import math
    rgba = [[255, 0, 0, 255, 0, 255, 0, 128], [0, 0, 255, 0, 255, 255, 255, 255]]
    angle = 0.5
    inverse_rotation = [(math.cos(angle) * u - math.sin(angle) * v, math.sin(angle) * u + math.cos(angle) * v)
                        for u, v in UVS]
    for name, stored, transform in (
            ("texture_transform.gltf", [(2 * u - 1, 2 * v - 1) for u, v in UVS],
             {"offset": [0.5, 0.5], "scale": [0.5, 0.5]}),
            ("texture_transform_rotation.gltf", inverse_rotation, {"rotation": angle})):
        document, data = quad_document()
        builder = extend(document, data)
        document["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = builder.add(
            pack("<2f", stored), FLOAT, "VEC2", 4)
        document["buffers"][0]["byteLength"] = len(builder.data)
        transformed = textured(embed(document, builder.data), png(2, 2, 4, rgba))
        transformed["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
            "KHR_texture_transform": transform}
        transformed["extensionsUsed"] = ["KHR_texture_transform"]
        transformed["extensionsRequired"] = ["KHR_texture_transform"]
        write_json(name, transformed)

    # KHR_materials_pbrSpecularGlossiness: the diffuse factor and texture give the alpha
    # (metallic-roughness has a fallback without texture that must not win).
    document, data = quad_document()
    rgba = [[255, 0, 0, 255, 0, 255, 0, 128], [0, 0, 255, 0, 255, 255, 255, 255]]
    spec_gloss = textured(embed(document, data), png(2, 2, 4, rgba))
    material = spec_gloss["materials"][0]
    material["extensions"] = {"KHR_materials_pbrSpecularGlossiness": {
        "diffuseFactor": material["pbrMetallicRoughness"]["baseColorFactor"],
        "diffuseTexture": {"index": 0}}}
    material["pbrMetallicRoughness"] = {"baseColorFactor": [1.0, 1.0, 1.0, 1.0]}
    spec_gloss["extensionsUsed"] = ["KHR_materials_pbrSpecularGlossiness"]
    spec_gloss["extensionsRequired"] = ["KHR_materials_pbrSpecularGlossiness"]
    write_json("spec_gloss.gltf", spec_gloss)

    # Emission: emissiveFactor x KHR_materials_emissive_strength, with an emissive texture
    # read through the base colour's UVs (emissive.gltf), or through TEXCOORD_1 while the
    # base colour reads TEXCOORD_0 (emissive_other_uvs.gltf: Penumbra keeps one UV set).
    rgba = [[255, 0, 0, 255, 0, 255, 0, 128], [0, 0, 255, 0, 255, 255, 255, 255]]
    emissive = textured(embed(*quad_document()), png(2, 2, 4, rgba))
    emissive["materials"][0]["emissiveFactor"] = [1.0, 0.5, 0.25]
    emissive["materials"][0]["emissiveTexture"] = {"index": 0}
    emissive["materials"][0]["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}
    emissive["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    write_json("emissive.gltf", emissive)
    second_set = json.load(open(os.path.join(HERE, "texcoord1.gltf")))
    second_set["materials"][0]["emissiveFactor"] = [1.0, 1.0, 1.0]
    second_set["materials"][0]["emissiveTexture"] = {"index": 0}  # texCoord 0, the base colour reads 1
    write_json("emissive_other_uvs.gltf", second_set)
    negative = json.load(open(os.path.join(HERE, "emissive.gltf")))
    negative["materials"][0]["emissiveFactor"] = [1.0, -0.5, 0.0]
    write_json("emissive_negative.gltf", negative)
    bad_strength = json.load(open(os.path.join(HERE, "emissive.gltf")))
    bad_strength["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = "bright"
    write_json("emissive_bad_strength.gltf", bad_strength)

    # Bent normals: the quad faces +Y, its shading normals lean far from it, to
    # normalize(0, 0.3, -1) (stood up by a 90 degree turn about X, the face looks along +Z
    # and the normals mostly up): lit from above and behind, the face is turned away.
    document, data = quad_document()
    builder = extend(document, data)
    length = (0.3 ** 2 + 1.0) ** 0.5
    bent = [(0.0, 0.3 / length, -1.0 / length)] * 4
    document["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = builder.add(pack("<3f", bent), FLOAT, "VEC3", 4)
    document["materials"][0]["alphaMode"] = "OPAQUE"
    document["buffers"][0]["byteLength"] = len(builder.data)
    write_json("bent_normals.gltf", embed(document, builder.data))

    # Broken sparse accessors: an index past the end, indices that do not increase.
    sparse = json.load(open(os.path.join(HERE, "sparse.gltf")))
    position = sparse["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
    past_end = copy.deepcopy(sparse)
    past_end["accessors"][position]["count"] = 2
    past_end["accessors"][position]["sparse"]["count"] = 2
    write_json("sparse_index_out_of_range.gltf", past_end)


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

    # A required extension Penumbra cannot honour is refused by name (Draco and meshopt
    # compression are decoded: tests/unit/test_gltf_compression.cpp).
    variant("basisu_required.gltf", lambda d: d.update(extensionsUsed=["KHR_texture_basisu"],
                                                       extensionsRequired=["KHR_texture_basisu"]))

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
    write_conformance_fixtures()
    write_malformed_fixtures()
