#!/usr/bin/env python3
"""Makes MultiUVBox.gltf from the Khronos BoxTextured sample: a second texture-coordinate set
(TEXCOORD_1, a lightmap-style atlas: each face of the box in its own cell of a 3 x 2 grid, laid out
from the face's positions, so that its seams are not those of TEXCOORD_0) and an occlusion texture
on it (the box's own texture, `texCoord: 1`). Deterministic: run it again and the file is the same.

    python3 samples/multiuv/make_multiuv_box.py samples/khronos/BoxTextured/BoxTextured.gltf \
        samples/multiuv/MultiUVBox.gltf
"""
import base64
import json
import struct
import sys


def main(source, target):
    doc = json.load(open(source))
    buffer = doc["buffers"][0]
    data = base64.b64decode(buffer["uri"].split(",", 1)[1])
    prim = doc["meshes"][0]["primitives"][0]
    position = doc["accessors"][prim["attributes"]["POSITION"]]
    normal = doc["accessors"][prim["attributes"]["NORMAL"]]

    def read_vec3(accessor):
        view = doc["bufferViews"][accessor["bufferView"]]
        start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
        return [struct.unpack_from("<3f", data, start + 12 * i) for i in range(accessor["count"])]

    positions, normals = read_vec3(position), read_vec3(normal)
    # Faces by their normal: each gets a cell, its vertices laid out over the two other axes.
    faces = sorted({tuple(round(c) for c in n) for n in normals})
    uv1 = []
    for p, n in zip(positions, normals):
        face = faces.index(tuple(round(c) for c in n))
        axis = max(range(3), key=lambda k: abs(n[k]))
        a, b = [k for k in range(3) if k != axis]
        cell_u, cell_v = face % 3, face // 3
        # Positions are in [-0.5, 0.5]: a margin of a tenth of a cell on every side.
        u = (cell_u + 0.1 + 0.8 * (p[a] + 0.5)) / 3.0
        v = (cell_v + 0.1 + 0.8 * (p[b] + 0.5)) / 2.0
        uv1.append((u, v))
    # The source shares one buffer view among three vertex accessors without a byteStride and gives
    # accessors a "byteStride" member, both of which the glTF-Validator reports: one view each here.
    for accessor in doc["accessors"]:
        accessor.pop("byteStride", None)
    for name in ("POSITION", "NORMAL", "TEXCOORD_0"):
        accessor = doc["accessors"][prim["attributes"][name]]
        shared = doc["bufferViews"][accessor["bufferView"]]
        size = accessor["count"] * (12 if accessor["type"] == "VEC3" else 8)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": shared.get("byteOffset", 0) + accessor.get("byteOffset", 0),
                                   "byteLength": size, "target": 34962})
        accessor["bufferView"] = len(doc["bufferViews"]) - 1
        accessor["byteOffset"] = 0
    packed = b"".join(struct.pack("<2f", u, v) for u, v in uv1)
    offset = len(data)
    data += packed
    buffer["byteLength"] = len(data)
    buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")
    doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(packed), "target": 34962})
    doc["accessors"].append({"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126, "count": len(uv1),
                             "type": "VEC2", "min": [min(u for u, _ in uv1), min(v for _, v in uv1)],
                             "max": [max(u for u, _ in uv1), max(v for _, v in uv1)]})
    prim["attributes"]["TEXCOORD_1"] = len(doc["accessors"]) - 1
    doc["materials"][0]["occlusionTexture"] = {"index": 0, "texCoord": 1, "strength": 0.5}
    doc["materials"][0]["name"] = "lightmapped"
    doc["asset"]["generator"] = "ellicast samples/multiuv/make_multiuv_box.py from Khronos BoxTextured"
    with open(target, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main(*sys.argv[1:3])
