#!/usr/bin/env python3
"""An independent format 1.14 decoder, written from spec/format.md alone (Python standard library only),
checked against the expected decodes of the conformance vectors.

    python3 spec/vectors/check_vectors.py            # every vector; exit 1 on any difference
    python3 spec/vectors/check_vectors.py --dump valid/minimal   # annotated fields of one vector

It re-derives everything the JSON states (container errors, damaged regions, packet results,
rejections, counters, stream info, every element's integers and dequantized values, digests; for
format 1.1 the scene graph, materials, textures and what a receiver shows of them, spec section 15, and
a 1.0 decoder's view of the same file; for format 1.2 the MANIFEST layout, every packet digest, and the
authentication of a signed recording with the vectors' key, spec section 16, with SHA-256 from hashlib
and Ed25519 verification written here from RFC 8032, and the POINTS_REPAIR packets of spec section 17:
their checks, the blocks a decoder holds and the points it recovers, with GF(2^8) written here; for
format 1.3 the MATERIAL_EXTENSIONS patches of spec section 18, with a strict JSON reader written here
from RFC 8259 and the rules of spec 18.2, their texture references and what a receiver shows, and
the CONNECTIVITY packets of spec section 19: their checks, the pieces, and the exact triangle list
decoded with a range decoder written here, candidates found by sorting every point, and the
CONNECTIVITY_REPAIR packets of spec 19.5: their checks, the rows held and the source symbols solved for
with the GF(2^8) code of section 17; for format 1.4 the ANIMATION packets of spec section 20: their checks
and comparisons, the keys held by index, and the animations a receiver shows, spec 20.2; for format 1.5 the
SKIN and JOINT_WEIGHTS packets and the node record's skin of spec section 21: their checks and
comparisons, the joints and influence records held, and the nodes a receiver shows skinned, spec 21.3; for
format 1.6 the MORPH_DELTAS and MORPH_ANIMATION packets and the mesh record's target field of spec section 22:
their checks and comparisons, the displacement records held (their i16 integers against the object's scales,
and the displacements as one f32 multiplication each) and morph keys held, the meshes a receiver shows with
their targets and the morph tracks it plays, spec 22.4; for format 1.7 the object entry's map fields and the
POINT_MAP and MAPPED_POINTS packets of spec section 23: their checks and comparisons, the Rice-coded trees of
the fragments decoded here, the ranks of spec 23.2, the records held but not placed and those placed, and
POINTS_REPAIR over mapped records, spec 23.5; for format 1.8 the object entry's surface-normals flag and the
NORMALS packets of spec section 24: their checks and comparisons, the normal entries held by index, and the
surface normal of every point of an exact object, summed here over its exact triangle list, spec 24.3; for
format 1.9 the MANIFEST scheme 2 of spec section 25: its layout with the content_id, and the bindings of
the authenticated digests judged against each stream id's content, spec 25.2; for format 1.10 the CAMERA and
LIGHT packets and the node record's camera and light fields of spec section 26: their checks (the limits of
glTF and KHR_lights_punctual on the f32 values) and comparisons, and the cameras and lights a receiver shows
on its nodes, spec 26.4; for format 1.11 the EXACT_MESH and EXACT_MESH_REPAIR packets of spec section 27: their
checks (those of CONNECTIVITY and CONNECTIVITY_REPAIR with carried_count, and one kind of exact layer per object),
and the coded mesh decoded with the same range decoder, the carried vertices with their attributes, spec 27.2; for
format 1.12 the EXTRAS packets of spec section 28: their checks, the description and text count comparisons, the
fragments kept by byte, and the CRC-32C and JSON checks of a whole text, spec 28.1; for format 1.13 the
REQUIRED_EXTENSION packets of spec section 29: their checks, the name count and name comparisons, spec 29.1;
for format 1.14 the TEXCOORDS packets of spec section 30: their checks, the set count, range and record comparisons,
and the further texture-coordinate records held by set and index, spec 30.1) so
that a disagreement between the spec text and the reference library shows up as a failing vector. Every complete texture is also checked to be a file of its
image_type: a PNG file (chunk CRCs, IHDR, the inflated image data of the size IHDR announces) or a
JPEG file (its marker structure: SOI, one frame header, the tables each scan uses, entropy-coded data,
EOI at the end).
"""
import hashlib
import json
import math
from fractions import Fraction
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
MAGIC = b"\xE1LCS"
SIGNATURE = b"\x89ELC\r\n\x1a\n"
KNOWN_10 = {1: "STREAM_INFO", 2: "ELLIPSOIDS", 3: "POINTS"}
# Format 1.1 types (spec sections 4 and 15).
KNOWN_11 = {0x10: "SCENE", 0x11: "MATERIAL", 0x12: "TEXTURE_FRAGMENT"}
# Format 1.2 (spec sections 4, 16 and 17).
KNOWN_12 = {0x20: "MANIFEST", 0x04: "POINTS_REPAIR"}
# Format 1.3 (spec sections 4, 18 and 19).
KNOWN_13 = {0x13: "MATERIAL_EXTENSIONS", 0x05: "CONNECTIVITY", 0x06: "CONNECTIVITY_REPAIR"}
# Format 1.4 (spec sections 4 and 20).
KNOWN_14 = {0x14: "ANIMATION"}
# Format 1.5 (spec sections 4 and 21).
KNOWN_15 = {0x15: "SKIN", 0x07: "JOINT_WEIGHTS"}
# Format 1.6 (spec sections 4 and 22).
KNOWN_16 = {0x16: "MORPH_ANIMATION", 0x08: "MORPH_DELTAS"}
# Format 1.7 (spec sections 4 and 23): both critical, both belong to an object.
KNOWN_17 = {0x09: "MAPPED_POINTS", 0x0A: "POINT_MAP"}
# Format 1.8 (spec sections 4 and 24): skippable, belongs to an object.
KNOWN_18 = {0x0B: "NORMALS"}
# Format 1.9 (spec section 25) adds no type: MANIFEST scheme 2 (decode_manifest, authenticate).
# Format 1.10 (spec sections 4 and 26): skippable, stream-level.
KNOWN_110 = {0x17: "CAMERA", 0x18: "LIGHT"}
# Format 1.11 (spec sections 4 and 27): skippable, belongs to an object.
KNOWN_111 = {0x0C: "EXACT_MESH", 0x0D: "EXACT_MESH_REPAIR"}
# Format 1.12 (spec sections 4 and 28): skippable, stream-level.
KNOWN_112 = {0x19: "EXTRAS"}
# Format 1.13 (spec sections 4 and 29): skippable, stream-level.
KNOWN_113 = {0x1A: "REQUIRED_EXTENSION"}
# Format 1.14 (spec sections 4 and 30): skippable, belongs to an object.
KNOWN_114 = {0x0E: "TEXCOORDS"}
NAME_BYTES = set(b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_")
EXTRAS_KINDS = ("asset", "scene", "node", "mesh", "material", "texture", "animation", "skin", "camera", "light",
                "morph animation")
SCENE_TYPES = set(KNOWN_11) | {0x13, 0x14, 0x15, 0x16} | set(KNOWN_110) | set(KNOWN_112) | set(KNOWN_113)  # JOINT_WEIGHTS and MORPH_DELTAS belong to an object
# The real numbers pi and pi / 2, exactly enough: every f32 is a double, and none lies between pi and
# the double nearest it (spec 26.2, 26.3 compare the f32 values with the real numbers).
PI = Fraction(314159265358979323846264338327950288, 10 ** 35)
PATHS = ("translation", "rotation", "scale")
INTERPOLATIONS = ("LINEAR", "STEP", "CUBICSPLINE")
NONE = 0xFFFF
SLOTS = ("base_color", "metallic_roughness", "normal", "occlusion", "emissive")


def crc32c(data, crc=0):
    c = crc ^ 0xFFFFFFFF
    for b in data:
        c ^= b
        for _ in range(8):
            c = (c >> 1) ^ (0x82F63B78 & -(c & 1))
    return c ^ 0xFFFFFFFF


def f32(x):
    """Round a real number to the nearest binary32, as the spec's 'rounded to f32'."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


# Binary32 rounds (to nearest, ties to even) every real of magnitude 2^128 - 2^103 or more, half-way
# between the largest f32 and 2^128 included, to infinity.
F32_INFINITE_FROM = 2 ** 128 - 2 ** 103


def f32_sum_infinite(a, b):
    """Spec 5.3: whether a + b, computed exactly and rounded to f32, is infinite."""
    return abs(Fraction(a) + Fraction(b)) >= F32_INFINITE_FROM


class Bits:
    """LSB-first bit reader (spec 1.1)."""

    def __init__(self, data):
        self.value = int.from_bytes(data, "little")
        self.pos = 0

    def get(self, n):
        v = (self.value >> self.pos) & ((1 << n) - 1)
        self.pos += n
        return v


def parse_packet(buf, pos, end, datagram=False):
    """Spec 11.1 steps 1..8. Returns (reason, header, size)."""
    n = end - pos
    if n < 24:
        return "too short", None, 0
    if buf[pos:pos + 4] != MAGIC:
        return "bad magic", None, 0
    major, minor, ptype, flags = buf[pos + 4], buf[pos + 5], buf[pos + 6], buf[pos + 7]
    if major != 1:
        return "unsupported major version", None, 0
    stream_id, sequence, object_id, length = struct.unpack_from("<IIHH", buf, pos + 8)
    size = 24 + length
    if size > 65000:
        return "oversized", None, 0
    if size > n:
        return "truncated", None, 0
    if crc32c(buf[pos:pos + 20 + length]) != struct.unpack_from("<I", buf, pos + 20 + length)[0]:
        return "bad checksum", None, 0
    if ptype == 0:
        return "invalid type", None, 0
    if datagram and size != n:
        return "length mismatch", None, 0
    h = dict(major=major, minor=minor, type=ptype, flags=flags, stream_id=stream_id, sequence=sequence,
             object_id=object_id, payload_length=length, payload=bytes(buf[pos + 20:pos + 20 + length]))
    return None, h, size


def read_container(buf):
    if len(buf) < 8 or buf[:8] != SIGNATURE:
        return "bad container signature", [], []
    if len(buf) < 12:
        return "too short", [], []
    if buf[8] != 1:
        return "unsupported container version", [], []
    packets, damaged = [], []
    pos = 12
    while pos < len(buf):
        reason, h, size = parse_packet(buf, pos, len(buf))
        if reason is None:
            packets.append((pos, size, h))
            pos += size
            continue
        nxt = pos + 1
        while nxt < len(buf):
            if buf[nxt] == 0xE1 and parse_packet(buf, nxt, len(buf))[0] is None:
                break
            nxt += 1
        damaged.append(dict(offset=pos, length=nxt - pos, reason=reason))
        pos = nxt
    return None, packets, damaged


def decode_stream_info(p, minor=9):
    """Spec 5.1..5.3. Returns (fields, object_count, first_object, entries) or None if malformed. `minor`: the
    packet's version_minor (the entries' map fields are read only from 1.7 on, spec 23.1, the surface-normals
    flag only from 1.8 on, spec 24.1)."""
    if len(p) < 32:
        return None
    info_size, entry_size, packet_size = struct.unpack_from("<HHH", p, 0)
    pb, nb, tb, cb, enc = p[6], p[7], p[8], p[9], p[10]
    content_id, object_count, first_object, entry_count, grid_hint = struct.unpack_from("<IHHHH", p, 12)
    coverage, seed = struct.unpack_from("<fI", p, 24)
    if info_size < 32 or entry_size < 44 or len(p) != info_size + entry_count * entry_size:
        return None
    if not (128 <= packet_size <= 65000 and 8 <= pb <= 16 and 4 <= nb <= 16 and 4 <= tb <= 16 and 2 <= cb <= 16):
        return None
    if enc != 0 or not math.isfinite(coverage) or first_object + entry_count > object_count:
        return None
    entries = []
    for i in range(entry_count):
        e = info_size + i * entry_size
        ox, oy, oz, scale, ne, npts = struct.unpack_from("<ffffII", p, e)
        kind, attrs = p[e + 24], p[e + 25]
        flags = struct.unpack_from("<H", p, e + 26)[0]
        to = struct.unpack_from("<ff", p, e + 28)
        ts = struct.unpack_from("<ff", p, e + 36)
        floats = (ox, oy, oz, scale) + to + ts
        if not all(math.isfinite(v) for v in floats) or not scale > 0 or min(ts) < 0:
            return None
        # The frame's far corner and the texture-coordinate range's end must be finite in f32.
        if any(f32_sum_infinite(o, scale) for o in (ox, oy, oz)) or any(f32_sum_infinite(to[k], ts[k]) for k in (0, 1)):
            return None
        if kind not in (0, 1) or attrs & 0xF0 or (attrs & 8 and not attrs & 4) or (kind == 1 and ne != 0):
            return None
        # Format 1.7 (spec 23.1): map_level at 44, map_batch at 46, read only from a packet that says 1.7 or
        # later whose entries are at least 48 bytes; otherwise both are 0 (bytes after 43 are a later field).
        level, batch = 0, 0
        if minor >= 7 and entry_size >= 48:
            level, batch = p[e + 44], struct.unpack_from("<H", p, e + 46)[0]
            if level >= pb or (level == 0 and batch != 0) or (level > 0 and batch == 0):
                return None
        # Format 1.8 (spec 24.1): flags bit 9, read only from a packet that says 1.8 or later (otherwise 0).
        # When set, the entry MUST be a surface (kind 0) with flags bit 8 set and attributes bit 0 clear.
        surface_normals = minor >= 8 and bool(flags & 0x200)
        if surface_normals and (kind != 0 or not flags & 0x100 or attrs & 1):
            return None
        entries.append(dict(frame_origin=[ox, oy, oz], frame_scale=scale, ellipsoid_count=ne, point_count=npts,
                            kind="surface" if kind == 0 else "point set", attributes=attrs,
                            texcoord_origin=list(to), texcoord_scale=list(ts),
                            # Spec 19: flags bit 8, the exact layer; it means nothing for a point set. From
                            # 1.3 on it is compared (5.4); the other bits of the field are not.
                            exact_layer=bool(flags & 0x100) and kind == 0,
                            # Compared like the other fields (5.4); an entry without them compares as 0, 0.
                            map_level=level, map_batch=batch,
                            # Compared like the other fields (5.4, 24.1); 0 when not read.
                            surface_normals=surface_normals))
    fields = dict(packet_size=packet_size, position_bits=pb, normal_bits=nb, texcoord_bits=tb, color_bits=cb,
                  ellipsoid_encoding=enc, content_id=content_id, grid_hint=grid_hint, coverage_target=coverage,
                  seed=seed)
    return fields, object_count, first_object, entries


def record_bits(info, obj):
    """B of spec 7.1, or for a mapped object B_m of spec 23.4."""
    return sum(record_widths(info, obj))


def decode_batch(p, record, count_bits=None):
    """ELLIPSOIDS (record = 128 bits) or POINTS batch (spec 6, 7): (first, [raw records]) or None."""
    if len(p) < 8:
        return None
    first, count = struct.unpack_from("<IH", p, 0)
    if len(p) != 8 + (count * record + 7) // 8 or first + count > 0xFFFFFFFF:
        return None
    bits = Bits(p[8:])
    return first, [bits for _ in range(count)]


def unpack_ellipsoid(bits):
    return [bits.get(15), bits.get(15), bits.get(15), bits.get(13), bits.get(13), bits.get(13), bits.get(2),
            bits.get(14), bits.get(14), bits.get(14)]


def unpack_point(bits, info, obj):
    """A point record (spec 7.1), or for a mapped object a mapped record (spec 23.4: its offset, then the
    attributes)."""
    return [bits.get(n) for n in record_widths(info, obj)]


def dequantize_ellipsoid(q, obj):
    s, o = obj["frame_scale"], obj["frame_origin"]
    center = [f32(o[i] + q[i] * s / 32767) for i in range(3)]
    radii = [f32(q[3 + i] * s / 8191) for i in range(3)]
    three = [(v / 16383 * 2 - 1) / math.sqrt(2) for v in q[7:10]]
    d = math.sqrt(max(0.0, 1 - sum(v * v for v in three)))
    quat = list(three)
    quat.insert(q[6], d)
    n = math.sqrt(sum(v * v for v in quat))
    return dict(center=center, radii=radii, rotation=[f32(v / n) for v in quat])


def sgn(v):
    return -1.0 if v < 0 else 1.0


def decode_octahedral(qu, qv, bits):
    """Spec 8.3: the unit normal of the octahedral integers (qu, qv) of `bits` bits each, rounded to f32."""
    nm = (1 << bits) - 1
    u, v = qu / nm * 2 - 1, qv / nm * 2 - 1
    z = 1 - abs(u) - abs(v)
    x, y = ((1 - abs(v)) * sgn(u), (1 - abs(u)) * sgn(v)) if z < 0 else (u, v)
    n = math.sqrt(x * x + y * y + z * z)
    return [f32(x / n), f32(y / n), f32(z / n)]


def dequantize_point(q, info, obj):
    a = obj["attributes"]
    s, o = obj["frame_scale"], obj["frame_origin"]
    pm = (1 << info["position_bits"]) - 1
    out = dict(position=[f32(o[i] + q[i] / pm * s) for i in range(3)])
    k = 3
    if a & 1:
        out["normal"] = decode_octahedral(q[k], q[k + 1], info["normal_bits"])
        k += 2
    if a & 2:
        tm = (1 << info["texcoord_bits"]) - 1
        out["texcoord"] = [f32(obj["texcoord_origin"][i] + q[k + i] / tm * obj["texcoord_scale"][i]) for i in range(2)]
        k += 2
    if a & 4:
        cm = (1 << info["color_bits"]) - 1
        out["color"] = [f32(v / cm) for v in q[k:]]
    return out


def fnv(words):
    h = 0xCBF29CE484222325
    for w in words:
        for i in range(4):
            h ^= (w >> (8 * i)) & 0xFF
            h = (h * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


class Body:
    """Bounded little-endian reads from a record body or payload; reading past the end sets `failed`."""

    def __init__(self, data):
        self.data, self.pos, self.failed = data, 0, False

    def take(self, fmt):
        n = struct.calcsize(fmt)
        if self.pos + n > len(self.data):
            self.failed = True
            return (0,) * len(fmt.lstrip("<"))
        v = struct.unpack_from(fmt, self.data, self.pos)
        self.pos += n
        return v

    def name(self):
        (n,) = self.take("<B")
        if self.failed or self.pos + n > len(self.data):
            self.failed = True
            return ""
        # Names that are not UTF-8 are shown with U+FFFD for each maximal ill-formed subpart (spec 15.1).
        v = self.data[self.pos:self.pos + n].decode("utf-8", errors="replace")
        self.pos += n
        return v


def finite(values):
    return all(math.isfinite(v) for v in values)


def decode_scene(p, minor=6):
    """Spec 15.1: ((node_count, mesh_count), nodes, meshes) or None when malformed. `minor`: the packet's
    version_minor (a node's skin is read only from 1.5 on, spec 21; a mesh's targets only from 1.6 on, spec 22)."""
    if len(p) < 8:
        return None
    node_count, mesh_count, record_count = struct.unpack_from("<HHH", p, 0)
    pos, nodes, meshes = 8, [], []
    for _ in range(record_count):
        if pos + 3 > len(p):
            return None
        kind, length = struct.unpack_from("<BH", p, pos)
        pos += 3
        if pos + length > len(p):
            return None
        b = Body(p[pos:pos + length])
        pos += length
        if kind == 1:
            index, parent, mesh, flags = b.take("<HHHB")
            n = dict(index=index, parent=parent, mesh=mesh, name=b.name())
            if flags & 1:
                n["matrix"] = list(b.take("<16f"))
            else:
                n["translation"], n["rotation"], n["scale"] = list(b.take("<3f")), list(b.take("<4f")), list(b.take("<3f"))
            # Format 1.5 (spec 21): in a packet that says 1.5 or later, a u16 skin after the transform when
            # two bytes follow it; a record without them (one stray byte is not a field) has none. Bytes
            # after it, and any bytes after the transform in an older packet, are ignored.
            n["skin"] = b.take("<H")[0] if minor >= 5 and not b.failed and len(b.data) - b.pos >= 2 else NONE
            # Format 1.10 (spec 26.1): in a packet that says 1.10 or later, a u16 camera after the skin when two
            # bytes follow it, then a u16 light when two more follow; a field not read is 0xFFFF.
            n["camera"] = b.take("<H")[0] if minor >= 10 and not b.failed and len(b.data) - b.pos >= 2 else NONE
            n["light"] = b.take("<H")[0] if minor >= 10 and not b.failed and len(b.data) - b.pos >= 2 else NONE
            floats = n.get("matrix", []) + n.get("translation", []) + n.get("rotation", []) + n.get("scale", [])
            if b.failed or index >= node_count or parent == index or (parent != NONE and parent >= node_count) \
                    or (mesh != NONE and mesh >= mesh_count) or not finite(floats):
                return None
            nodes.append(n)
        elif kind == 2:
            (index,) = b.take("<H")
            name = b.name()
            (count,) = b.take("<H")
            prims = [dict(zip(("object", "material"), b.take("<HH"))) for _ in range(count)]
            if b.failed or index >= mesh_count:
                return None
            # Format 1.6 (spec 22): in a packet that says 1.6 or later, when at least one byte follows the
            # primitives, a u8 target_count and that many f32 default weights, which MUST all be there and be
            # finite. A record without the field has 0 targets; bytes after it (or after the primitives in an
            # older packet) are ignored.
            weights = []
            if minor >= 6 and len(b.data) - b.pos >= 1:
                (targets,) = b.take("<B")
                if len(b.data) - b.pos < 4 * targets:
                    return None
                weights = list(b.take("<%df" % targets)) if targets else []
                if not finite(weights):
                    return None
            meshes.append(dict(index=index, name=name, primitives=prims, weights=weights))
        # other kinds: skipped by their length
    if pos != len(p):
        return None
    return (node_count, mesh_count), nodes, meshes


def decode_material(p):
    """Spec 15.2: the material's fields or None when malformed."""
    if len(p) < 88:
        return None
    index, count, alpha, double, name_length = struct.unpack_from("<HHBBB", p, 0)
    if len(p) != 88 + name_length:
        return None
    factors = struct.unpack_from("<10f", p, 8)
    refs = [(struct.unpack_from("<H", p, 48 + 8 * k)[0], p[48 + 8 * k + 2], struct.unpack_from("<f", p, 48 + 8 * k + 4)[0])
            for k in range(5)]
    if index >= count or alpha > 2 or not finite(list(factors) + [r[2] for r in refs]):
        return None
    # Byte 7, flags: bit 0 has_extensions (spec 18.1), compared like the other fields; bits 1..7 reserved.
    return dict(index=index, material_count=count, alpha=alpha, double_sided=double != 0, factors=list(factors),
                refs=refs, name=p[88:].decode("utf-8", errors="replace"), has_extensions=bool(p[7] & 1))


def node_json(n, viewed=False):
    out = dict(n, parent=None if n["parent"] == NONE else n["parent"], mesh=None if n["mesh"] == NONE else n["mesh"],
               skin=None if n["skin"] == NONE else n["skin"], camera=None if n["camera"] == NONE else n["camera"],
               light=None if n["light"] == NONE else n["light"])
    if not viewed:  # the README: the keys of format 1.10 are there only in a file of format 1.10
        del out["camera"], out["light"]
    return out


def decode_camera(p):
    """Spec 26.2: dict of the camera's fields, or None when malformed (rules 1..6)."""
    if len(p) < 24 or len(p) != 24 + p[5]:
        return None
    index, count, projection = struct.unpack_from("<HHB", p, 0)
    a, b, znear, zfar = struct.unpack_from("<4f", p, 8)
    if index >= count or projection > 1 or not finite([a, b, znear, zfar]):
        return None
    if projection == 0:
        if a < 0 or b <= 0 or Fraction(b) >= PI or znear <= 0 or zfar < 0 or (zfar != 0 and zfar <= znear):
            return None
    elif a <= 0 or b <= 0 or znear < 0 or zfar <= znear:
        return None
    return dict(index=index, count=count, projection=projection, a=a, b=b, znear=znear, zfar=zfar, name=p[24:])


def decode_light(p):
    """Spec 26.3: dict of the light's fields, or None when malformed (rules 1..7)."""
    if len(p) < 36 or len(p) != 36 + p[5]:
        return None
    index, count, kind = struct.unpack_from("<HHB", p, 0)
    values = struct.unpack_from("<7f", p, 8)
    color, intensity, rng, inner, outer = list(values[:3]), values[3], values[4], values[5], values[6]
    if index >= count or kind > 2 or not finite(values):
        return None
    if any(c < 0 or c > 1 for c in color) or intensity < 0 or rng < 0:
        return None
    if (kind == 0 and rng != 0) or (kind != 2 and (inner != 0 or outer != 0)):
        return None
    if kind == 2 and (inner < 0 or outer <= inner or Fraction(outer) > PI / 2):
        return None
    return dict(index=index, count=count, type=kind, color=color, intensity=intensity, range=rng, inner=inner,
                outer=outer, name=p[36:])


def decode_skin(p):
    """Spec 21.1: (skin, skin_count, joint_count, first_joint, skeleton, name bytes, joints) or None when
    malformed; each joint (node, 16 matrix entries)."""
    if len(p) < 14:
        return None
    skin, table, joint_count, first, count, skeleton, name_length = struct.unpack_from("<HHHHHHB", p, 0)
    # Python integers do not overflow: first + count is the true sum.
    if len(p) != 14 + name_length + 66 * count or skin >= table or joint_count == 0 or count == 0 \
            or first + count > joint_count:
        return None
    joints = []
    for k in range(count):
        at = 14 + name_length + 66 * k
        node = struct.unpack_from("<H", p, at)[0]
        matrix = list(struct.unpack_from("<16f", p, at + 2))
        if not finite(matrix):
            return None
        joints.append((node, matrix))
    return skin, table, joint_count, first, skeleton, p[14:14 + name_length], joints


def decode_joint_weights(p):
    """Spec 21.2, the checks that need no stream info: (first_index, records) or None when malformed; each
    record (joints, weights), n being their length."""
    if len(p) < 8:
        return None
    first, count, size = struct.unpack_from("<IHB", p, 0)
    if count == 0 or size not in (1, 2) or first + count > 2 ** 32 - 1:
        return None
    pos, records = 8, []
    for _ in range(count):
        if pos >= len(p):
            return None
        n = p[pos]
        pos += 1
        if not 1 <= n <= 4 or pos + n * (size + 1) > len(p):
            return None
        joints = [int.from_bytes(p[pos + size * k:pos + size * (k + 1)], "little") for k in range(n)]
        pos += size * n
        weights = list(p[pos:pos + n])
        pos += n
        if 0 in weights or sum(weights) != 255 or len(set(joints)) != n:
            return None
        records.append((joints, weights))
    if pos != len(p):
        return None
    return first, records


def decode_morph_deltas(p):
    """Spec 22.1, the checks that need no stream info: (first_index, target_count, attributes, scales, records) or
    None when malformed; scales the S = target_count * a f32 scales, each record the list of its 3 * S integers
    (slot by slot, x, y, z; a slot whose mask bit is clear 0, 0, 0)."""
    if len(p) < 8:
        return None
    first, count, targets, attributes = struct.unpack_from("<IHBB", p, 0)
    if count == 0 or targets == 0 or attributes == 0 or attributes & ~3:
        return None
    slots = targets * bin(attributes).count("1")
    if len(p) < 8 + 4 * slots:
        return None
    scales = list(struct.unpack_from("<%df" % slots, p, 8))
    # NaN > 0 is false: a NaN scale is caught here too; -0.0 > 0 is false as in IEEE 754.
    if not finite(scales) or not all(s > 0 for s in scales) or any(s >= 2.0 ** 113 for s in scales):
        return None
    mask_size = (slots + 7) // 8
    pos = 8 + 4 * slots
    records = []
    for _ in range(count):
        if pos + mask_size > len(p):
            return None  # a record runs past the payload (its mask)
        mask = int.from_bytes(p[pos:pos + mask_size], "little")  # slot k is bit k mod 8 of byte k // 8
        pos += mask_size
        if mask >> slots:
            return None  # a mask bit from S on is set
        record = []
        for k in range(slots):
            if mask >> k & 1:
                if pos + 6 > len(p):
                    return None  # a record runs past the payload (a vector)
                record.extend(struct.unpack_from("<3h", p, pos))
                pos += 6
            else:
                record.extend((0, 0, 0))
        records.append(record)
    # Python integers do not overflow: first + count is the true sum.
    if pos != len(p) or first + count > 2 ** 32 - 1:
        return None  # bytes follow the last record, or the run passes 2^32 - 1
    return first, targets, attributes, scales, records


def f32_product(q, scale):
    """Spec 22.1: the displacement q * scale computed as one f32 multiplication. The product of an i16 and an
    f32 has at most 16 + 24 significant bits, so the double product is exact; rounding it to f32 once (to
    nearest, ties to even) gives the spec's result, infinite past the f32 range (struct refuses to pack that)."""
    x = q * scale
    return math.copysign(math.inf, x) if abs(x) >= F32_INFINITE_FROM else f32(x)


def decode_morph_animation(p):
    """Spec 22.2: (animation, animation_count, track, track_count, joins, name bytes, desc, first_key, keys) or
    None when malformed; desc = (node, target_count C, interpolation, key_count), each key (time, V weights)."""
    if len(p) < 26:
        return None
    index, table, track, track_count, node, joins, c, interp, count, key_count, first, name_length = \
        struct.unpack_from("<HHHHHHBBHIIB", p, 0)
    if c == 0 or interp > 2:  # checked before the length, which depends on them through V
        return None
    v = 3 * c if interp == 2 else c  # a cubic spline key: the in-tangents, the values, the out-tangents
    if len(p) != 26 + name_length + count * 4 * (1 + v) or index >= table or track >= track_count \
            or key_count == 0 or (interp == 2 and key_count < 2) or count == 0 or first + count > key_count:
        return None
    keys = []
    for k in range(count):
        key = struct.unpack_from("<%df" % (1 + v), p, 26 + name_length + 4 * (1 + v) * k)
        # -0.0 < 0 is false in Python as in IEEE 754: a time of -0 is not negative.
        if not finite(key) or key[0] < 0 or (keys and not key[0] > keys[-1][0]):
            return None
        keys.append(key)
    return index, table, track, track_count, joins, p[26:26 + name_length], (node, c, interp, key_count), first, keys


def material_json(m):
    f = m["factors"]
    textures = {slot: None if ref[0] == NONE else dict(texture=ref[0], texcoord=ref[1], scale=ref[2])
                for slot, ref in zip(SLOTS, m["refs"])}
    return dict(index=m["index"], name=m["name"], alpha_mode=("OPAQUE", "MASK", "BLEND")[m["alpha"]],
                alpha_cutoff=f[9], double_sided=m["double_sided"], base_color=f[0:4], metallic=f[4], roughness=f[5],
                emissive=f[6:9], textures=textures, has_extensions=m["has_extensions"])


# ---- Format 1.3: MATERIAL_EXTENSIONS patches (spec 18.2, 18.3) ----

class PatchError(Exception):
    pass


NUMBER_DIGITS = "0123456789"


class PatchReader:
    """One JSON text by RFC 8259 section 2 with the limits of spec 18.2 rules 3..7. Values become
    ("object", [(name, value), ...]) with members in text order, ("array", [values]), ("string", text),
    ("number", token) or ("literal", word)."""

    def __init__(self, text):
        self.s, self.i = text, 0

    def fail(self):
        raise PatchError()

    def ws(self):
        while self.i < len(self.s) and self.s[self.i] in " \t\n\r":
            self.i += 1

    def document(self):
        self.ws()
        v = self.value(1)
        self.ws()
        if self.i != len(self.s):
            self.fail()  # a second value, or anything else after the first
        return v

    def value(self, depth):
        if self.i >= len(self.s):
            self.fail()
        c = self.s[self.i]
        if c == "{":
            return self.object(depth)
        if c == "[":
            return self.array(depth)
        if c == '"':
            return ("string", self.string())
        for word in ("true", "false", "null"):
            if self.s.startswith(word, self.i):
                self.i += len(word)
                return ("literal", word)
        return ("number", self.number())

    def object(self, depth):
        if depth > 32:  # rule 7: the patch itself is depth 1
            self.fail()
        self.i += 1
        members, names = [], set()
        self.ws()
        if self.s.startswith("}", self.i):
            self.i += 1
            return ("object", members)
        while True:
            self.ws()
            if not self.s.startswith('"', self.i):
                self.fail()
            name = self.string()
            if name in names:  # rule 6, names compared decoded
                self.fail()
            names.add(name)
            self.ws()
            if not self.s.startswith(":", self.i):
                self.fail()
            self.i += 1
            self.ws()
            members.append((name, self.value(depth + 1)))
            self.ws()
            if self.s.startswith(",", self.i):
                self.i += 1
            elif self.s.startswith("}", self.i):
                self.i += 1
                return ("object", members)
            else:
                self.fail()

    def array(self, depth):
        if depth > 32:
            self.fail()
        self.i += 1
        elements = []
        self.ws()
        if self.s.startswith("]", self.i):
            self.i += 1
            return ("array", elements)
        while True:
            self.ws()
            elements.append(self.value(depth + 1))
            self.ws()
            if self.s.startswith(",", self.i):
                self.i += 1
            elif self.s.startswith("]", self.i):
                self.i += 1
                return ("array", elements)
            else:
                self.fail()

    def hex4(self):
        h = self.s[self.i:self.i + 4]
        if len(h) != 4 or any(c not in "0123456789abcdefABCDEF" for c in h):
            self.fail()
        self.i += 4
        return int(h, 16)

    def string(self):
        self.i += 1  # the opening quote
        out = []
        short = {'"': '"', "\\": "\\", "/": "/", "b": "\b", "f": "\f", "n": "\n", "r": "\r", "t": "\t"}
        while self.i < len(self.s):
            c = self.s[self.i]
            self.i += 1
            if c == '"':
                return "".join(out)
            if ord(c) < 0x20:  # rule 4: unescaped control character
                self.fail()
            if c != "\\":
                out.append(c)
                continue
            if self.i >= len(self.s):
                self.fail()
            e = self.s[self.i]
            self.i += 1
            if e in short:
                out.append(short[e])
            elif e == "u":
                cp = self.hex4()
                if 0xDC00 <= cp <= 0xDFFF:  # rule 4: a low surrogate not preceded by a high one
                    self.fail()
                if 0xD800 <= cp <= 0xDBFF:  # rule 4: must be directly followed by a low one
                    if not self.s.startswith("\\u", self.i):
                        self.fail()
                    self.i += 2
                    low = self.hex4()
                    if not 0xDC00 <= low <= 0xDFFF:
                        self.fail()
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00)
                out.append(chr(cp))
            else:
                self.fail()
        self.fail()  # the text ended inside a string

    def number(self):
        start = self.i

        def digits():
            at = self.i
            while self.i < len(self.s) and self.s[self.i] in NUMBER_DIGITS:
                self.i += 1
            return self.i > at

        if self.s.startswith("-", self.i):
            self.i += 1
        if self.s.startswith("0", self.i):
            self.i += 1
        elif not digits():
            self.fail()
        if self.s.startswith(".", self.i):
            self.i += 1
            if not digits():
                self.fail()
        if self.i < len(self.s) and self.s[self.i] in "eE":
            self.i += 1
            if self.i < len(self.s) and self.s[self.i] in "+-":
                self.i += 1
            if not digits():
                self.fail()
        token = self.s[start:self.i]
        if not math.isfinite(float(token)):  # rule 5: float() rounds to the nearest binary64
            self.fail()
        return token


CORE_INFOS_TOP = ("normalTexture", "occlusionTexture", "emissiveTexture")
CORE_INFOS_PBR = ("baseColorTexture", "metallicRoughnessTexture")


def patch_shape_ok(root):
    """Spec 18.2, the fixed shape."""
    def is_object(v):
        return v[0] == "object"

    def extensions_ok(v):
        return is_object(v) and all(is_object(ext) for _, ext in v[1])

    def core_info_ok(v):
        return is_object(v) and all(n == "extensions" and extensions_ok(x) for n, x in v[1])

    if not is_object(root):
        return False
    for name, v in root[1]:
        if name == "extensions":
            ok = extensions_ok(v)
        elif name in CORE_INFOS_TOP:
            ok = core_info_ok(v)
        elif name == "pbrMetallicRoughness":
            ok = is_object(v) and all(
                extensions_ok(x) if n == "extensions" else n in CORE_INFOS_PBR and core_info_ok(x) for n, x in v[1])
        else:
            ok = False
        if not ok:
            return False
    return True


def patch_references(v, name, path, out):
    """Spec 18.2's texture rules and 18.3's references (path, texture) in document order: the order of
    their opening brace, which is a depth-first walk in text order."""
    if v[0] == "object":
        members = dict(v[1])
        is_reference = name is not None and name.endswith("Texture") and "index" in members
        if is_reference or name == "KHR_texture_transform":
            tc = members.get("texCoord")
            if tc is not None and tc != ("number", "0"):
                raise PatchError()
        if is_reference:
            kind, token = members["index"]
            if kind != "number" or not token or any(c not in NUMBER_DIGITS for c in token) or \
                    (len(token) > 1 and token[0] == "0") or int(token) > 65534:
                raise PatchError()
            out.append(dict(path=path, texture=int(token)))
        for n, x in v[1]:
            patch_references(x, n, n if path == "" else path + "/" + n, out)
    elif v[0] == "array":
        for k, x in enumerate(v[1]):
            patch_references(x, None, "%s/%d" % (path, k), out)


def check_patch(data):
    """Spec 18.2 rules 2..8 on the patch bytes: its texture references, or None when malformed."""
    try:
        text = data.decode("utf-8")  # strict: no surrogates, overlong forms or code points past U+10FFFF
    except UnicodeDecodeError:
        return None
    try:
        root = PatchReader(text).document()
        if not patch_shape_ok(root):
            return None
        refs = []
        patch_references(root, None, "", refs)
        return refs
    except PatchError:
        return None


def fnv_bytes(data):
    h = 0xCBF29CE484222325
    for b in data:
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


def png_problem(data):
    """None when `data` is a well-formed 8-bit PNG (chunk CRCs, IHDR, inflated size), else what is wrong."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return "no PNG signature"
    pos, ihdr, idat = 8, None, b""
    while pos + 12 <= len(data):
        (length,) = struct.unpack_from(">I", data, pos)
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack_from(">I", data, pos + 8 + length)
        if zlib.crc32(kind + body) != crc:
            return "chunk %r: bad CRC" % kind
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    if ihdr is None or ihdr[2] != 8:
        return "no 8-bit IHDR"
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(ihdr[3])
    if channels is None or len(zlib.decompress(idat)) != ihdr[1] * (1 + ihdr[0] * channels):
        return "image data does not match IHDR"
    return None


def jpeg_problem(data):
    """None when `data` is a well-formed JPEG file (ITU-T T.81 markers: SOI, one frame header, the tables
    each scan uses defined before it, entropy-coded data, EOI as the last 2 bytes), else what is wrong.
    The structure is checked; the entropy-coded data is not decoded."""
    if data[:2] != b"\xff\xd8":
        return "no JPEG SOI marker"
    pos, frame, scans = 2, None, 0
    quant, huffman = set(), set()  # defined quantization tables; (class, id) of Huffman tables
    while True:
        if pos >= len(data) or data[pos] != 0xFF:
            return "no marker at byte %d" % pos
        while pos < len(data) and data[pos] == 0xFF:  # fill bytes
            pos += 1
        if pos >= len(data):
            return "truncated at byte %d" % pos
        marker, pos = data[pos], pos + 1
        if marker == 0xD9:  # EOI
            if frame is None or scans == 0:
                return "EOI before a frame and a scan"
            return None if pos == len(data) else "%d bytes after EOI" % (len(data) - pos)
        if marker == 0x01 or 0xD0 <= marker <= 0xD8:
            return "marker %02X outside a scan at byte %d" % (marker, pos - 2)
        if pos + 2 > len(data):
            return "truncated at byte %d" % pos
        (length,) = struct.unpack_from(">H", data, pos)
        if length < 2 or pos + length > len(data):
            return "segment %02X at byte %d runs past the end" % (marker, pos - 2)
        body, pos = data[pos + 2:pos + length], pos + length
        if marker in (0xC0, 0xC1, 0xC2, 0xC3, 0xC5, 0xC6, 0xC7, 0xC9, 0xCA, 0xCB, 0xCD, 0xCE, 0xCF):
            if frame is not None:
                return "a second frame header"
            if len(body) < 6 or len(body) != 6 + 3 * body[5]:
                return "frame header of the wrong length"
            _, height, width, count = struct.unpack_from(">BHHB", body)
            if height == 0 or width == 0 or count not in (1, 2, 3, 4):
                return "frame of %d x %d with %d components" % (width, height, count)
            components = {body[6 + 3 * i]: body[8 + 3 * i] & 15 for i in range(count)}
            frame = (marker, components)
        elif marker == 0xDB:  # DQT: (Pq, Tq) then 64 values of 1 or 2 bytes, repeated
            at = 0
            while at < len(body):
                precision, table = body[at] >> 4, body[at] & 15
                at += 1 + 64 * (2 if precision else 1)
                quant.add(table)
            if at != len(body):
                return "DQT segment of the wrong length"
        elif marker == 0xC4:  # DHT: (Tc, Th), 16 counts, the values, repeated
            at = 0
            while at + 17 <= len(body):
                huffman.add((body[at] >> 4, body[at] & 15))
                at += 17 + sum(body[at + 1:at + 17])
            if at != len(body):
                return "DHT segment of the wrong length"
        elif marker == 0xDA:  # SOS, then entropy-coded data up to the next marker that is not RSTn
            if frame is None:
                return "a scan before the frame header"
            if len(body) < 4 or len(body) != 4 + 2 * body[0]:
                return "scan header of the wrong length"
            start, ah = body[1 + 2 * body[0]], body[3 + 2 * body[0]] >> 4
            arithmetic = frame[0] >= 0xC9
            for i in range(body[0]):
                selector, tables = body[1 + 2 * i], body[2 + 2 * i]
                if selector not in frame[1]:
                    return "a scan names component %d, not in the frame" % selector
                if frame[0] & 3 != 3 and frame[1][selector] not in quant:  # lossless (n & 3 == 3): none
                    return "a scan uses an undefined quantization table"
                needed = []  # arithmetic coding needs no tables
                if not arithmetic and frame[0] & 3 == 3:  # lossless: DC tables only
                    needed = [(0, tables >> 4)]
                elif not arithmetic and frame[0] & 3 == 2:  # progressive
                    needed = [(1, tables & 15)] if start > 0 else ([] if ah else [(0, tables >> 4)])
                elif not arithmetic:
                    needed = [(0, tables >> 4), (1, tables & 15)]
                if not set(needed) <= huffman:
                    return "a scan uses an undefined Huffman table"
            scans += 1
            while True:
                if pos + 1 >= len(data):
                    return "entropy-coded data runs to the end of the file (truncated, no EOI)"
                if data[pos] == 0xFF and data[pos + 1] != 0 and not 0xD0 <= data[pos + 1] <= 0xD7:
                    break
                pos += 2 if data[pos] == 0xFF else 1
        # APPn, COM, DRI, DAC and the like: skipped by their length


# ------------------------------------------------------------------------------------------------
# Format 1.2: signed streams (spec 16). Ed25519 verification after RFC 8032 section 5.1.7, with the
# checks spec 16.3 pins.

ED_P = 2 ** 255 - 19
ED_L = 2 ** 252 + 27742317777372353535851937790883648493
ED_D = (-121665 * pow(121666, ED_P - 2, ED_P)) % ED_P
ED_SQRT_M1 = pow(2, (ED_P - 1) // 4, ED_P)


def ed_add(a, b):
    """Points in extended coordinates (X, Y, Z, T), x = X/Z, y = Y/Z, x*y = T/Z."""
    x1, y1, z1, t1 = a
    x2, y2, z2, t2 = b
    A = (y1 - x1) * (y2 - x2) % ED_P
    B = (y1 + x1) * (y2 + x2) % ED_P
    C = 2 * t1 * t2 * ED_D % ED_P
    D = 2 * z1 * z2 % ED_P
    E, F, G, H = B - A, D - C, D + C, B + A
    return (E * F % ED_P, G * H % ED_P, F * G % ED_P, E * H % ED_P)


def ed_mul(k, point):
    result = (0, 1, 1, 0)
    while k:
        if k & 1:
            result = ed_add(result, point)
        point = ed_add(point, point)
        k >>= 1
    return result


def ed_decode(b):
    """A 32-byte point encoding to extended coordinates, or None (RFC 8032 5.1.3)."""
    y = int.from_bytes(b, "little")
    sign = y >> 255
    y &= (1 << 255) - 1
    if y >= ED_P:
        return None
    u, v = (y * y - 1) % ED_P, (ED_D * y * y + 1) % ED_P
    x = u * pow(v, 3, ED_P) * pow(u * pow(v, 7, ED_P), (ED_P - 5) // 8, ED_P) % ED_P
    if (v * x * x - u) % ED_P != 0:
        x = x * ED_SQRT_M1 % ED_P
        if (v * x * x - u) % ED_P != 0:
            return None
    if x == 0 and sign:
        return None
    if x & 1 != sign:
        x = ED_P - x
    return (x, y, 1, x * y % ED_P)


ED_B = ed_decode(bytes.fromhex("5866666666666666666666666666666666666666666666666666666666666666"))


def ed_encode(P):
    zi = pow(P[2], ED_P - 2, ED_P)
    x, y = P[0] * zi % ED_P, P[1] * zi % ED_P
    return (y | (x & 1) << 255).to_bytes(32, "little")


def ed_small_order(P):
    Q = ed_mul(8, P)
    return Q[0] % ED_P == 0 and (Q[1] - Q[2]) % ED_P == 0


def ed25519_verify(public, message, signature):
    """Spec 16.3: S < L; A a canonical encoding of a point not of small order; R not of small order;
    and the encoding of [S]B - [k]A equal to R byte for byte (k = SHA-512(R || A || M) mod L)."""
    A, R = ed_decode(public), ed_decode(signature[:32])
    S = int.from_bytes(signature[32:], "little")
    if A is None or S >= ED_L or ed_small_order(A):
        return False
    if R is not None and ed_small_order(R):
        return False
    k = int.from_bytes(hashlib.sha512(signature[:32] + public + message).digest(), "little") % ED_L
    minus_kA = ed_mul(k, (ED_P - A[0], A[1], A[2], ED_P - A[3]))
    return ed_encode(ed_add(ed_mul(S, ED_B), minus_kA)) == signature[:32]


def ed25519_public_key(seed):
    """The public key of a 32-byte seed (RFC 8032 5.1.5), for the vectors' key."""
    h = hashlib.sha512(seed).digest()
    a = int.from_bytes(h[:32], "little")
    a &= (1 << 254) - 8
    a |= 1 << 254
    return ed_encode(ed_mul(a, ED_B))


VECTORS_KEY = ed25519_public_key(bytes(range(32)))
MANIFEST_CONTEXT = b"ellicast manifest"


def digest_input(h):
    """Spec 16.1: header and payload with the sequence bytes zeroed."""
    header = MAGIC + bytes([h["major"], h["minor"], h["type"], h["flags"]]) + struct.pack(
        "<IIHH", h["stream_id"], 0, h["object_id"], h["payload_length"])
    return header + h["payload"]


def packet_digest(h):
    return hashlib.sha256(digest_input(h)).digest()[:16]


def decode_manifest(payload):
    """Spec 16.2, and for scheme 2 spec 25.1: None when malformed, dict(scheme=...) alone for a later scheme,
    else every field (content_id None for scheme 1)."""
    if len(payload) == 0:
        return None
    scheme = payload[0]
    if scheme not in (1, 2):
        return dict(scheme=scheme)
    # Scheme 2 has the content_id (u32) at offset 24, before the digests: 4 bytes more.
    fixed = 88 if scheme == 1 else 92
    if len(payload) < fixed:
        return None
    part, part_count, n, packet_count, first = struct.unpack_from("<HHHII", payload, 2)
    if len(payload) != fixed + 16 * n or part_count == 0 or part >= part_count or first + n > packet_count:
        return None
    content_id = struct.unpack_from("<I", payload, 24)[0] if scheme == 2 else None
    at = fixed - 64  # the first digest
    return dict(scheme=scheme, part=part, part_count=part_count, packet_count=packet_count, first=first,
                key_id=payload[16:24], content_id=content_id,
                digests=[payload[at + 16 * i:at + 16 + 16 * i] for i in range(n)], signature=payload[at + 16 * n:])


def authenticate(packets):
    """Spec 16.3 for a recording, with the bindings of spec 25.2 (last paragraph): every MANIFEST first, then
    each stream id's content from its first STREAM_INFO in file order that rules 1 and 2 pass, then every
    other packet in file order by rules 1 to 3."""
    key_id = hashlib.sha256(VECTORS_KEY).digest()[:8]
    counters = dict(passed=0, manifests_verified=0, manifests_repeated=0, manifests_failed=0, malformed=0,
                    unknown_scheme=0, not_authenticated=0)
    verdicts, manifests = {}, []
    # Spec 25.2: digest -> its bindings, the content_id of every verified scheme-2 part that lists it, and None
    # (the mark "unbound") when a verified scheme-1 part lists it.
    bindings, verified = {}, set()
    for offset, size, h in packets:
        if h["type"] != 0x20:
            continue
        m = decode_manifest(h["payload"])
        entry = dict(offset=offset)
        if m is None:
            entry["malformed"] = True
            counters["malformed"] += 1
            verdicts[offset] = "malformed payload"
        elif m["scheme"] not in (1, 2):
            entry.update(malformed=False, scheme=m["scheme"])
            counters["unknown_scheme"] += 1
            verdicts[offset] = "skipped"
        else:
            # Spec 16.2, 25.1: the signed message is made the same way for both schemes.
            message = MANIFEST_CONTEXT + digest_input(h)[:-64]
            ok = m["key_id"] == key_id and ed25519_verify(VECTORS_KEY, message, m["signature"])
            entry.update(malformed=False, scheme=m["scheme"], part=m["part"], part_count=m["part_count"],
                         packet_count=m["packet_count"], first=m["first"], key_id=m["key_id"].hex(),
                         digests=[d.hex() for d in m["digests"]],
                         signed_message_sha256=hashlib.sha256(message).hexdigest(),
                         signature=m["signature"].hex(), verified=ok)
            if m["scheme"] == 2:
                entry["content_id"] = m["content_id"]
            digest = packet_digest(h)
            if digest in verified:
                counters["manifests_repeated"] += 1
                verdicts[offset] = "repeat"
            elif not ok:
                counters["manifests_failed"] += 1
                verdicts[offset] = "bad manifest signature"
            else:
                verified.add(digest)
                counters["manifests_verified"] += 1
                for d in m["digests"]:
                    bindings.setdefault(d, set()).add(m["content_id"])
                verdicts[offset] = "manifest"
        manifests.append(entry)

    def passes(h, digest, content):
        """Spec 25.2 rules 1 to 3 for a packet other than MANIFEST; `content` that of its stream id, or None."""
        bound = bindings.get(digest)
        if bound is None:  # not authenticated: no verified part lists it
            return False
        if None in bound:  # rule 1: unbound
            return True
        if h["type"] == 1 and len(h["payload"]) >= 16:  # rule 2: a STREAM_INFO of its own content, and the stream's
            own = struct.unpack_from("<I", h["payload"], 12)[0]
            return own in bound and (content is None or content == own)
        return content is not None and content in bound  # rule 3; a stream without a content passes nothing

    # Spec 25.2: each stream id's content, from the first STREAM_INFO of at least 16 payload bytes, in file
    # order, that rules 1 and 2 pass (a shorter one sets nothing).
    contents = {}
    for offset, size, h in packets:
        if h["type"] == 1 and len(h["payload"]) >= 16 and h["stream_id"] not in contents and \
                passes(h, packet_digest(h), None):
            contents[h["stream_id"]] = struct.unpack_from("<I", h["payload"], 12)[0]
    plist = []
    passed = Receiver()
    for offset, size, h in packets:
        digest = packet_digest(h)
        if h["type"] != 0x20:
            if passes(h, digest, contents.get(h["stream_id"])):
                verdicts[offset] = "pass"
                counters["passed"] += 1
                passed.add(h, offset)
            else:
                verdicts[offset] = "not authenticated"
                counters["not_authenticated"] += 1
        plist.append(dict(offset=offset, digest=digest.hex(), verdict=verdicts[offset]))
    info = dict(passed.info, object_count=passed.object_count) if passed.info is not None else None
    return dict(key=VECTORS_KEY.hex(), key_id=key_id.hex(), manifests=manifests, packets=plist, counters=counters,
                authenticated=dict(counters=passed.counters, stream_info=info, objects=objects_json(passed)))


# ------------------------------------------------------------------------------------------------
# Format 1.2: repair packets (spec 17). GF(2^8): bytes are polynomials over GF(2), bit 0 the constant
# term, multiplied modulo x^8 + x^4 + x^3 + x^2 + 1 (0x11D).


def gf_mul_slow(a, b):
    product = 0
    while b:
        if b & 1:
            product ^= a
        b >>= 1
        a <<= 1
        if a & 0x100:
            a ^= 0x11D
    return product


GF_MUL = [[gf_mul_slow(a, b) for b in range(256)] for a in range(256)]
GF_INV = [0] + [next(b for b in range(1, 256) if GF_MUL[a][b] == 1) for a in range(1, 256)]
# The examples of spec 17.2.
assert GF_MUL[0x02][0x80] == 0x1D and GF_MUL[0x53][0xCA] == 0x8F and GF_INV[2] == 0x8E and GF_INV[3] == 0xF4


def cauchy(r, j):
    """C(r, j) = inv(r XOR j), spec 17.2."""
    return GF_INV[r ^ j]


def repair_fields(p):
    """Spec 17.3, the checks without stream info (step 11): (first_index, batch, k, row) or None."""
    if len(p) < 9:
        return None
    first, batch, k, row = struct.unpack_from("<IHBB", p, 0)
    if batch == 0 or k == 0 or row < k or row > 254 or first + (k - 1) * batch > 0xFFFFFFFF:
        return None
    return first, batch, k, row


def pack_records(records, widths, length):
    """Point records bit-packed LSB-first as in a POINTS payload (spec 1.1, 7), zero bits up to `length` bytes."""
    value, pos = 0, 0
    for q in records:
        for v, n in zip(q, widths):
            value |= v << pos
            pos += n
    return value.to_bytes(length, "little")


def record_widths(info, obj):
    """The bit width of each integer of a point record (spec 7.1), in order; for an object whose map_level L is
    not 0, of a mapped record (spec 23.4): the offset's D = position_bits - L bits per coordinate."""
    a = obj["attributes"]
    w = [info["position_bits"] - obj["map_level"]] * 3
    if a & 1:
        w += [info["normal_bits"]] * 2
    if a & 2:
        w += [info["texcoord_bits"]] * 2
    if a & 4:
        w += [info["color_bits"]] * (4 if a & 8 else 3)
    return w


def solve_gf(matrix, rhs):
    """Solves matrix * x = rhs over GF(2^8): matrix u x u, rhs u byte strings; returns the u byte strings x."""
    u = len(matrix)
    m = [list(row) for row in matrix]
    y = [bytearray(v) for v in rhs]
    for col in range(u):
        pivot = next(r for r in range(col, u) if m[r][col])  # a Cauchy matrix: never singular
        m[col], m[pivot] = m[pivot], m[col]
        y[col], y[pivot] = y[pivot], y[col]
        scale = GF_MUL[GF_INV[m[col][col]]]
        m[col] = [scale[v] for v in m[col]]
        y[col] = bytearray(scale[v] for v in y[col])
        for r in range(u):
            f = m[r][col]
            if r != col and f:
                mul = GF_MUL[f]
                m[r] = [a ^ mul[b] for a, b in zip(m[r], m[col])]
                y[r] = bytearray(a ^ mul[b] for a, b in zip(y[r], y[col]))
    return [bytes(v) for v in y]


# ------------------------------------------------------------------------------------------------
# Format 1.7: mapped points (spec 23).


def mapped_rank(i, count, batch):
    """Spec 23.2: the rank of the point of index i < count, the points dealt to batches of `batch` indices."""
    batches = -(-count // batch)
    last = count - (batches - 1) * batch
    t, j = divmod(i, batch)
    return j * batches + t - max(0, j - last)


def morton_cell(code, level):
    """Spec 23.2: the cell (cx, cy, cz) of level `level` whose Morton code is `code`."""
    cell = [0, 0, 0]
    for b in range(level):
        for axis in range(3):
            cell[axis] |= (code >> (3 * b + axis) & 1) << b
    return cell


def point_map_header(p):
    """Spec 23.3, the fixed fields (step 11): (first_rank, point_total, root_level, rice, root_count) or None."""
    if len(p) < 12:
        return None
    first, total, root_level, rice, roots = struct.unpack_from("<IIBBH", p, 0)
    if total == 0 or rice > 15 or roots == 0:
        return None
    return first, total, root_level, rice, roots


class TreeEnd(Exception):
    """The tree of a POINT_MAP payload is malformed (spec 23.3, step 13)."""


def point_map_cells(p, level):
    """Spec 23.3, step 13, for an object mapped at `level` (its map_level L): the fragment's cells of level L in
    the order the tree reaches them, each (Morton code, count), or None when the payload is malformed."""
    first, total, root_level, rice, roots = point_map_header(p)
    if level == 0 or root_level > level:
        return None
    # The tree as a string of bits in stream order (LSB-first, spec 1.1): a unary run is then one find().
    stream = "".join(format(b, "08b")[::-1] for b in p[12:])
    at = 0
    cells, counted = [], [0]

    def field(n):
        nonlocal at
        if at + n > len(stream):
            raise TreeEnd()  # the bits end before the tree does
        v = int(stream[at:at + n][::-1], 2) if n else 0
        at += n
        return v

    def node(code, l):
        nonlocal at
        if l == level:
            end = stream.find("0", at)  # floor(v / 2^k) ones, then a zero
            if end < 0:
                raise TreeEnd()
            quotient = end - at
            at = end + 1
            v = (quotient << rice) | field(rice)
            cells.append((code, v + 1))
            counted[0] += v + 1
            # Every count is at least 1: once they pass point_total they cannot add up to it (the same reason;
            # this bounds the work by point_total as spec 23.3 says).
            if counted[0] > total:
                raise TreeEnd()
            return
        mask = field(8)
        if mask == 0:
            raise TreeEnd()
        for c in range(8):
            if mask >> c & 1:
                node(8 * code + c, l + 1)

    try:
        previous = None
        for _ in range(roots):
            code = field(3 * root_level)
            if previous is not None and code <= previous:
                return None  # a root's code not greater than the previous root's
            previous = code
            node(code, root_level)
    except TreeEnd:
        return None
    if counted[0] != total or len(p) != 12 + (at + 7) // 8:
        return None  # the counts do not add up to point_total, or bytes follow the tree's last byte
    return cells


# ------------------------------------------------------------------------------------------------
# Format 1.8: surface normals (spec 24).


def decode_texcoords(p):
    """Spec 30.1, every check of step 11: (first_index, set, set_count, (bits, origin, scale), [(qu, qv)]) or None
    when the payload is shorter than 28 bytes, count is 0, set_count is 0 or above 7, set is 0 or above set_count, bits
    is outside 4..16, the run passes index 2^32 - 1, a range component is not finite, a scale is negative, an end
    (origin + scale, rounded to f32) is infinite, or the length is not 28 + ceil(2 bits count / 8). The reserved bytes
    9..11 and the padding bits are not looked at."""
    if len(p) < 28:
        return None
    first, count, set_, set_count, bits = struct.unpack_from("<IHBBB", p, 0)
    origin = struct.unpack_from("<2f", p, 12)
    scale = struct.unpack_from("<2f", p, 20)
    if count == 0 or not 1 <= set_count <= 7 or not 1 <= set_ <= set_count or not 4 <= bits <= 16 or \
            first + count > 0xFFFFFFFF:
        return None
    if not finite(origin + scale) or min(scale) < 0 or any(f32_sum_infinite(o, s) for o, s in zip(origin, scale)):
        return None
    if len(p) != 28 + (2 * bits * count + 7) // 8:
        return None
    b = Bits(p[28:])
    records = [(b.get(bits), b.get(bits)) for _ in range(count)]
    return first, set_, set_count, (bits, list(origin), list(scale)), records


def normals_header(p):
    """Spec 24.2, the fixed fields (step 11): (first_index, count, sent_count) or None."""
    if len(p) < 8:
        return None
    first, count, sent = struct.unpack_from("<IHH", p, 0)
    if count == 0 or sent > count or first + count > 0xFFFFFFFF:  # Python integers do not overflow
        return None
    return first, count, sent


def normals_entries(p, bits):
    """Spec 24.2, step 13 for the stream's normal_bits N: (first_index, [entry]) with each entry None (left to the
    surface) or (u, v) (sent), or None when the length is not 8 + ceil((count + 2 N sent_count) / 8) or the flags of
    value 1 are not sent_count in number. The padding bits are not looked at."""
    first, count, sent = normals_header(p)
    if len(p) != 8 + (count + 2 * bits * sent + 7) // 8:
        return None
    r = Bits(p[8:])
    flags = [r.get(1) for _ in range(count)]
    if sum(flags) != sent:
        return None
    entries = [None] * count
    for i, f in enumerate(flags):  # the sent normals follow all the flags, in index order
        if f:
            entries[i] = (r.get(bits), r.get(bits))
    return first, entries


def surface_normals(positions, triangles):
    """Spec 24.3: per point, S / |S| (S the sum over the corners at the point of theta * m / |m|, m = e1 x e2 in
    integers, for the corners where m != 0), or None when no corner contributes or S = 0."""
    S = [[0.0, 0.0, 0.0] for _ in positions]
    contributed = [False] * len(positions)
    for t in triangles:
        for c in range(3):
            i, j, k = t[c], t[(c + 1) % 3], t[(c + 2) % 3]
            e1 = [positions[j][a] - positions[i][a] for a in range(3)]
            e2 = [positions[k][a] - positions[i][a] for a in range(3)]
            m = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
            if m == [0, 0, 0]:
                continue  # exact: the triangle does not contribute
            l1 = math.sqrt(sum(v * v for v in e1))
            l2 = math.sqrt(sum(v * v for v in e2))
            lm = math.sqrt(sum(v * v for v in m))
            theta = math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(e1, e2)) / (l1 * l2))))
            for a in range(3):
                S[i][a] += theta * m[a] / lm
            contributed[i] = True
    out = []
    for s, c in zip(S, contributed):
        length = math.sqrt(sum(v * v for v in s))
        out.append([f32(v / length) for v in s] if c and length > 0 else None)
    return out


class Receiver:
    """Spec 11.1 steps 9..15 and 11.2."""

    def __init__(self, know_11=True):
        self.know_11 = know_11
        self.scene_counts = None  # (node_count, mesh_count) of the SCENE packets taken
        self.nodes, self.meshes, self.materials, self.textures = {}, {}, {}, {}
        self.patches = {}  # format 1.3: material index -> (patch bytes, texture references)
        self.animation_count = None  # format 1.4: that of the first ANIMATION packet accepted
        self.animations = {}  # index -> dict(track_count, name (bytes), tracks: index -> dict(desc, keys))
        self.skin_count = None  # format 1.5: that of the first SKIN packet accepted
        self.skins = {}  # index -> dict(joint_count, skeleton, name (bytes), joints: index -> (node, matrix))
        self.morph_count = None  # format 1.6: that of the first MORPH_ANIMATION packet accepted
        # index -> dict(track_count, joins, name (bytes), tracks: index -> dict(desc (node, C, interp, key_count), keys))
        self.morphs = {}
        self.material_count = None  # that of the materials and patches held
        self.camera_count, self.cameras = None, {}  # format 1.10: table size of the CAMERA packets, index -> fields
        self.light_count, self.lights = None, {}  # likewise for LIGHT
        self.extras_count, self.texts = None, {}  # format 1.12: text_count of the EXTRAS packets, (kind, index) -> text
        self.name_count, self.names = None, {}  # format 1.13: name_count of the REQUIRED_EXTENSION packets, index -> name
        self.stream_id = None
        self.info = None
        self.object_count = 0
        self.objects = []
        self.held = []
        self.counters = dict(accepted=0, duplicates=0, skipped=0, rejected=0, held=0)
        self.rejections = []
        self.newest_minor = 0

    def reject(self, offset, reason):
        self.counters["rejected"] += 1
        self.rejections.append(dict(offset=offset, reason=reason))
        return reason

    def add(self, h, offset):
        if self.stream_id is not None and h["stream_id"] != self.stream_id:
            return self.reject(offset, "stream mismatch")
        t = h["type"]
        if t not in KNOWN_10 and ((t not in KNOWN_11 and t not in KNOWN_12 and t not in KNOWN_13 and t not in KNOWN_14
                                   and t not in KNOWN_15 and t not in KNOWN_16 and t not in KNOWN_17 and t not in KNOWN_18
                                   and t not in KNOWN_110 and t not in KNOWN_111 and t not in KNOWN_112 and t not in KNOWN_113
                                   and t not in KNOWN_114)
                                  or not self.know_11):
            if not h["flags"] & 1:
                return self.reject(offset, "unknown critical type")
            self.stream_id = h["stream_id"]
            self.counters["skipped"] += 1
            self.newest_minor = max(self.newest_minor, h["minor"])
            return "skipped"
        if t == 1:
            result = self.stream_info(h, offset)
        elif t == 0x10:
            result = self.scene(h, offset)
        elif t == 0x11:
            result = self.material(h, offset)
        elif t == 0x12:
            result = self.fragment(h, offset)
        elif t == 0x13:
            result = self.extensions(h, offset)
        elif t == 0x14:
            result = self.animation(h, offset)
        elif t == 0x15:
            result = self.skin(h, offset)
        elif t == 0x16:
            result = self.morph_animation(h, offset)
        elif t in (0x17, 0x18):
            result = self.camera_light(h, offset)
        elif t == 0x19:
            result = self.extras(h, offset)
        elif t == 0x1A:
            result = self.required_extension(h, offset)
        elif t == 0x07 and decode_joint_weights(h["payload"]) is None:
            # Spec 21.2: checked at step 11, before the packet can be held.
            return self.reject(offset, "malformed payload")
        elif t == 0x08 and decode_morph_deltas(h["payload"]) is None:
            # Spec 22.1: checked at step 11, before the packet can be held.
            return self.reject(offset, "malformed payload")
        elif t == 0x20:
            # A decoder checks the layout (scheme 1, spec 16.2; scheme 2, spec 25.1; a later scheme's is not
            # checked) and takes nothing; verifying needs a key.
            if decode_manifest(h["payload"]) is None:
                return self.reject(offset, "malformed payload")
            self.counters["skipped"] += 1
            result = "skipped"
        elif t == 0x04 and repair_fields(h["payload"]) is None:
            # Spec 17.3: the fixed fields are checked at step 11, before the packet can be held.
            return self.reject(offset, "malformed payload")
        elif t == 0x0A and point_map_header(h["payload"]) is None:
            # Spec 23.3: the fixed fields are checked at step 11, before the packet can be held.
            return self.reject(offset, "malformed payload")
        elif t == 0x0B and normals_header(h["payload"]) is None:
            # Spec 24.2: the fixed fields are checked at step 11, before the packet can be held.
            return self.reject(offset, "malformed payload")
        elif t == 0x0E and decode_texcoords(h["payload"]) is None:
            # Spec 30.1: every check but those needing the object is made at step 11, before the packet can be held.
            return self.reject(offset, "malformed payload")
        else:
            result = self.object_packet(h, offset)
        if result in ("accepted", "duplicate", "held", "skipped"):
            self.stream_id = h["stream_id"]
            self.newest_minor = max(self.newest_minor, h["minor"])
        return result

    def stream_info(self, h, offset):
        if h["object_id"] != 0xFFFF:
            return self.reject(offset, "malformed payload")
        d = decode_stream_info(h["payload"], h["minor"])
        if d is None:
            return self.reject(offset, "malformed payload")
        fields, count, first, entries = d
        if self.info is not None:
            # Spec 5.4: f32 fields compare as numbers (Python floats: -0.0 == 0.0); the reserved fields
            # and the bytes after offset 43 of a longer entry are not in the dicts compared.
            if fields != self.info or count != self.object_count:
                return self.reject(offset, "stream mismatch")
        else:
            self.info, self.object_count = fields, count
            # points: by index, those placed (spec 23.4) for a mapped object; records (format 1.7): a mapped
            # object's records held, placed or not, as their integers (offset, then attributes); fragments: its
            # POINT_MAP fragments accepted, by first rank.
            # normals (format 1.8): an object's normal entries held, by point index (None: left to the surface).
            self.objects = [dict(info=None, ellipsoids={}, points={}, blocks={}, recovered=0, weights={},
                                 morph={}, morph_kind=None, records={}, fragments={}, normals={}, texsets=None)
                            for _ in range(count)]
            # Spec 11.1: held packets naming an object beyond the table are rejected now, in arrival order.
            for h, at in [x for x in self.held if x[0]["object_id"] >= count]:
                self.counters["held"] -= 1
                self.reject(at, "unknown object")
            self.held = [x for x in self.held if x[0]["object_id"] < count]
        for i, e in enumerate(entries):
            known = self.objects[first + i]["info"]
            if known is not None and known != e:
                return self.reject(offset, "stream mismatch")
        news = False
        for i, e in enumerate(entries):
            obj = self.objects[first + i]
            if obj["info"] is None:
                obj["info"] = e
                news = True
        if news:
            self.release()
        if news or not entries:
            self.counters["accepted"] += 1
            return "accepted"
        self.counters["duplicates"] += 1
        return "duplicate"

    def release(self):
        """Spec 11.1: once a STREAM_INFO part is taken in whole, every held packet whose object's entry has
        now arrived is checked, in the order the packets arrived (not grouped by object)."""
        ready = lambda x: self.objects[x[0]["object_id"]]["info"] is not None
        mine = [x for x in self.held if ready(x)]
        self.held = [x for x in self.held if not ready(x)]
        for h, offset in mine:
            self.counters["held"] -= 1
            self.object_packet(h, offset)

    def object_packet(self, h, offset):
        oid = h["object_id"]
        if self.info is not None and oid >= self.object_count:
            return self.reject(offset, "unknown object")
        if self.info is None or self.objects[oid]["info"] is None:
            self.held.append((h, offset))
            self.counters["held"] += 1
            return "held"
        obj = self.objects[oid]
        if h["type"] == 0x04:
            return self.repair(obj, h, offset)
        if h["type"] in (0x05, 0x0C):
            return self.connectivity(obj, h, offset, mesh=h["type"] == 0x0C)
        if h["type"] in (0x06, 0x0D):
            return self.connectivity_repair(obj, h, offset, mesh=h["type"] == 0x0D)
        if h["type"] == 0x07:
            return self.joint_weights(obj, h, offset)
        if h["type"] == 0x08:
            return self.morph_deltas(obj, h, offset)
        if h["type"] == 0x0A:
            return self.point_map(obj, h, offset)
        if h["type"] == 0x0B:
            return self.normals(obj, h, offset)
        if h["type"] == 0x0E:
            return self.texcoords(obj, h, offset)
        ellipsoids = h["type"] == 2
        mapped = obj["info"]["map_level"] > 0
        # Spec 23.4, step 13: POINTS for an object whose map_level is not 0, MAPPED_POINTS for one whose map_level
        # is 0, are malformed (as is a payload whose length does not match, below; the same reason).
        if not ellipsoids and (h["type"] == 0x09) != mapped:
            return self.reject(offset, "malformed payload")
        record = 128 if ellipsoids else record_bits(self.info, obj["info"])
        batch = decode_batch(h["payload"], record)
        if batch is None:
            return self.reject(offset, "malformed payload")
        first, readers = batch
        declared = obj["info"]["ellipsoid_count" if ellipsoids else "point_count"]
        if first + len(readers) > declared:
            return self.reject(offset, "index out of range")
        store = obj["ellipsoids"] if ellipsoids else self.held_store(obj)
        fresh = []
        for i, bits in enumerate(readers):
            q = unpack_ellipsoid(bits) if ellipsoids else unpack_point(bits, self.info, obj["info"])
            if first + i not in store:  # the first record received for an index is kept (7.2, 23.4)
                fresh.append(first + i)
                if mapped and not ellipsoids:
                    self.take_record(obj, first + i, q)
                else:
                    store[first + i] = q
        self.counters["accepted" if fresh else "duplicates"] += 1
        if fresh and not ellipsoids:
            # Spec 17.4: after accepting a POINTS packet that brings a point of a block with rows kept,
            # recover the block if it can be (23.5, 23.6: a MAPPED_POINTS packet that brings a record).
            for b in sorted(obj["blocks"].values(), key=lambda b: b["first"]):
                if b["rows"] and any(b["first"] <= i < b["first"] + b["count"] for i in fresh):
                    self.recover(obj, b)
        return "accepted" if fresh else "duplicate"

    @staticmethod
    def held_store(obj):
        """What spec 17 calls the points held, by index: for a mapped object its records, placed or not (23.6)."""
        return obj["records"] if obj["info"]["map_level"] else obj["points"]

    def take_record(self, obj, index, q):
        """Spec 23.4: a mapped record not held before is held, and placed at once when a fragment holding its
        rank has been accepted."""
        obj["records"][index] = q
        info = obj["info"]
        rank = mapped_rank(index, info["point_count"], info["map_batch"])
        for first, fragment in obj["fragments"].items():
            if first <= rank < first + fragment["total"]:
                self.place(obj, index, rank, first, fragment)
                break

    def place(self, obj, index, rank, first, fragment):
        """Spec 23.2: the point of rank `rank` lies in the cell of level L that holds it; its quantized position
        is that cell's corner (cell * 2^D on each axis) plus the offset its record carries."""
        d = self.info["position_bits"] - obj["info"]["map_level"]
        at = first
        for code, count in fragment["cells"]:
            if rank < at + count:
                break
            at += count
        cell = morton_cell(code, obj["info"]["map_level"])
        q = obj["records"][index]
        obj["points"][index] = [(cell[k] << d) + q[k] for k in range(3)] + q[3:]

    def point_map(self, obj, h, offset):
        """Spec 23.3 with the object's entry: step 13 (the tree), 14 (the ranks), 15 (against the fragments
        kept); then the records held whose rank the fragment holds are placed (23.4)."""
        p, info = h["payload"], obj["info"]
        first, total, _, _, _ = point_map_header(p)
        cells = point_map_cells(p, info["map_level"])
        if cells is None:
            return self.reject(offset, "malformed payload")
        if first + total > info["point_count"]:  # Python integers do not overflow
            return self.reject(offset, "index out of range")
        kept = obj["fragments"]
        if first in kept and kept[first]["cells"] == cells:
            return self.news(False)  # a duplicate, whatever its root_level and rice
        for g_first, g in kept.items():
            below = first + total <= g_first and cells[-1][0] < g["cells"][0][0]
            above = first >= g_first + g["total"] and cells[0][0] > g["cells"][-1][0]
            if not (below or above):
                return self.reject(offset, "stream mismatch")
        fragment = kept[first] = dict(total=total, cells=cells)
        for index in sorted(obj["records"]):
            if index not in obj["points"]:
                rank = mapped_rank(index, info["point_count"], info["map_batch"])
                if first <= rank < first + total:
                    self.place(obj, index, rank, first, fragment)
        return self.news(True)

    def normals(self, obj, h, offset):
        """Spec 24.2 with the object's entry: step 13 (the object has surface normals; the length and the flags),
        14 (the run inside point_count), 15 (each entry against the one held; nothing kept on a contradiction)."""
        if not obj["info"]["surface_normals"]:
            return self.reject(offset, "malformed payload")
        d = normals_entries(h["payload"], self.info["normal_bits"])
        if d is None:
            return self.reject(offset, "malformed payload")
        first, entries = d
        if first + len(entries) > obj["info"]["point_count"]:
            return self.reject(offset, "index out of range")
        held = obj["normals"]
        # Identical entries: both left to the surface, or both sent with the same u and v.
        if any(first + i in held and held[first + i] != e for i, e in enumerate(entries)):
            return self.reject(offset, "stream mismatch")
        fresh = [i for i in range(len(entries)) if first + i not in held]
        for i in fresh:
            held[first + i] = entries[i]
        return self.news(bool(fresh))

    def texcoords(self, obj, h, offset):
        """Spec 30.1 with the object's entry: step 13 (the object carries texture coordinates), 14 (the run inside
        point_count), 15 (set_count against the object's earlier packets, the range against the set's first packet,
        each record against the one held; nothing kept on a contradiction)."""
        if not obj["info"]["attributes"] & 2:
            return self.reject(offset, "malformed payload")
        first, set_, set_count, rng, records = decode_texcoords(h["payload"])
        if first + len(records) > obj["info"]["point_count"]:
            return self.reject(offset, "index out of range")
        sets = obj["texsets"]
        if sets is not None and len(sets) != set_count:
            return self.reject(offset, "stream mismatch")
        held = sets[set_ - 1] if sets is not None else None
        if held is not None and held["range"] is not None and held["range"] != rng:
            return self.reject(offset, "stream mismatch")
        have = held["records"] if held is not None else {}
        if any(first + i in have and have[first + i] != r for i, r in enumerate(records)):
            return self.reject(offset, "stream mismatch")
        fresh = [i for i in range(len(records)) if first + i not in have]
        if fresh:
            if sets is None:
                sets = obj["texsets"] = [dict(range=None, records={}) for _ in range(set_count)]
            held = sets[set_ - 1]
            if held["range"] is None:
                held["range"] = rng
            for i in fresh:
                held["records"][first + i] = records[i]
        return self.news(bool(fresh))

    def joint_weights(self, obj, h, offset):
        """Spec 21.2 with the object's entry: step 14, then each record against the one held (step 15)."""
        first, records = decode_joint_weights(h["payload"])
        if first + len(records) > obj["info"]["point_count"]:
            return self.reject(offset, "index out of range")
        held = obj["weights"]
        # Identical records: the same n, joints (as numbers) and weights, in the same order.
        if any(first + i in held and held[first + i] != r for i, r in enumerate(records)):
            return self.reject(offset, "stream mismatch")
        fresh = [i for i in range(len(records)) if first + i not in held]
        for i in fresh:
            held[first + i] = records[i]
        return self.news(bool(fresh))

    def morph_deltas(self, obj, h, offset):
        """Spec 22.1 with the object's entry: step 14, then the target count, attributes and scales and each
        record against those held (step 15)."""
        first, targets, attributes, scales, records = decode_morph_deltas(h["payload"])
        if first + len(records) > obj["info"]["point_count"]:
            return self.reject(offset, "index out of range")
        # The scales compare as numbers (a list of Python floats: element by element with ==).
        if obj["morph_kind"] is not None and obj["morph_kind"] != (targets, attributes, scales):
            return self.reject(offset, "stream mismatch")
        held = obj["morph"]
        # Records are identical when every slot holds the same three integers (a clear bit reads as 0, 0, 0).
        if any(first + i in held and held[first + i] != r for i, r in enumerate(records)):
            return self.reject(offset, "stream mismatch")
        fresh = [i for i in range(len(records)) if first + i not in held]
        if fresh:
            obj["morph_kind"] = (targets, attributes, scales)
            for i in fresh:
                held[first + i] = records[i]
        return self.news(bool(fresh))

    def layer_malformed(self, info, mesh, count, carried, size):
        """The checks of spec 19.1 on the fields a CONNECTIVITY and a CONNECTIVITY_REPAIR packet share (with the
        object's entry, step 13), and, for an EXACT_MESH or EXACT_MESH_REPAIR packet (`mesh`), those of spec 27.1:
        carried_count 1 .. 2^24, triangle_count at most 8 (point_count + carried_count), coded_size at most
        16 triangle_count + (16 + ceil(B / 8)) carried_count + 64 with B the bit size of a POINTS record of the
        object (spec 7.1, also for a mapped object). With carried = 0 the bounds are those of 19.1. Python integers
        do not overflow."""
        if mesh and (carried == 0 or carried > 1 << 24):
            return True
        B = sum(record_widths(self.info, dict(info, map_level=0)))
        return count == 0 or count > 8 * (info["point_count"] + carried) or info["kind"] == "point set" \
            or size > 16 * count + (16 + -(-B // 8)) * carried + 64

    def connectivity(self, obj, h, offset, mesh=False):
        """Spec 19.1 (CONNECTIVITY), or spec 27.1 (EXACT_MESH, `mesh`: the same with carried_count at offset 4), once
        the object's entry has arrived: pieces of the coded connectivity (coded mesh), keyed by byte offset like a
        texture's; complete once every byte arrived and the CRC-32C matches."""
        p, info = h["payload"], obj["info"]
        head = 20 if mesh else 16
        if len(p) <= head:
            return self.reject(offset, "malformed payload")
        if mesh:
            count, carried, size, crc, at = struct.unpack_from("<IIIII", p, 0)
        else:
            (count, size, crc, at), carried = struct.unpack_from("<IIII", p, 0), 0
        data = p[head:]
        if at + len(data) > size or self.layer_malformed(info, mesh, count, carried, size):
            return self.reject(offset, "malformed payload")
        c = self.new_connectivity(obj, mesh, count, carried, size, crc)
        # Spec 27.1: the first packet taken fixes the kind of the exact layer; then the description (19.1).
        if c["mesh"] != mesh or c["desc"] != (count, carried, size, crc):
            return self.reject(offset, "stream mismatch")
        if c["complete"]:
            return self.news(False)
        fresh = 0
        for k, b in enumerate(data):
            if at + k not in c["have"]:  # the first copy of a byte is kept
                c["have"][at + k] = b
                fresh += 1
        if not fresh:
            return self.news(False)
        if not self.complete_connectivity(c):
            return self.reject(offset, "stream mismatch")
        return self.news(True)

    @staticmethod
    def new_connectivity(obj, mesh, count, carried, size, crc):
        """An object's exact layer, from the first CONNECTIVITY, CONNECTIVITY_REPAIR, EXACT_MESH or EXACT_MESH_REPAIR
        packet that passed the well-formedness checks: its kind (spec 27.1: `mesh` for EXACT_MESH packets), its
        description (carried_count 0 for a CONNECTIVITY layer), the bytes held, and (spec 19.5) the symbol size L of
        its repair packets (None before one), the rows held with their symbols in the order accepted, and whether it
        was completed by solving for source symbols."""
        return obj.setdefault("connectivity", dict(mesh=mesh, desc=(count, carried, size, crc), have={}, complete=False,
                                                   coded=None, L=None, rows=[], recovered=False))

    def connectivity_repair(self, obj, h, offset, mesh=False):
        """Spec 19.5 (CONNECTIVITY_REPAIR), or spec 27.1 (EXACT_MESH_REPAIR, `mesh`: carried_count at offset 4, the
        other fields 4 bytes further), once the object's entry has arrived: a repair symbol over the coded
        connectivity (coded mesh)."""
        p, info = h["payload"], obj["info"]
        head = 20 if mesh else 16
        if len(p) < head:
            return self.reject(offset, "malformed payload")
        if mesh:
            count, carried, size, crc, L, row = struct.unpack_from("<IIIIHB", p, 0)
        else:
            (count, size, crc, L, row), carried = struct.unpack_from("<IIIHB", p, 0), 0
        k = -(-size // L) if L else 0
        # The rules of 19.1 (27.1) for the shared fields (and a coded connectivity of at least one byte, as a
        # CONNECTIVITY piece implies: see README), then those of 19.5.
        if size == 0 or self.layer_malformed(info, mesh, count, carried, size) or L == 0 or len(p) != head + L \
                or k > 254 or row < k:
            return self.reject(offset, "malformed payload")
        c = self.new_connectivity(obj, mesh, count, carried, size, crc)
        if c["mesh"] != mesh or c["desc"] != (count, carried, size, crc) or (c["L"] is not None and c["L"] != L):
            return self.reject(offset, "stream mismatch")
        c["L"] = L
        if c["complete"] or row in [r for r, _ in c["rows"]]:
            return self.news(False)
        c["rows"].append((row, p[head:]))
        if not self.complete_connectivity(c):
            return self.reject(offset, "stream mismatch")
        return self.news(True)

    @staticmethod
    def complete_connectivity(c):
        """Spec 19.5, then 19.1: when the held source symbols and rows number k or more, solve for the missing
        symbols with the first rows accepted; a solved symbol's bytes inside coded_size replace any held
        before; when every byte is held, check the CRC-32C. False on a mismatch (the bytes,
        rows and symbols are then discarded)."""
        count, carried, size, crc = c["desc"]
        have = c["have"]
        if len(have) < size and c["rows"]:
            L = c["L"]
            k = -(-size // L)
            span = lambda j: range(j * L, min((j + 1) * L, size))
            held = [j for j in range(k) if all(t in have for t in span(j))]
            missing = [j for j in range(k) if j not in held]
            if len(held) + len(c["rows"]) >= k:
                sources = {j: bytes(have[t] for t in span(j)).ljust(L, b"\0") for j in held}
                rows = c["rows"][:len(missing)]
                rhs = []
                for r, symbol in rows:
                    y = bytearray(symbol)
                    for j, sj in sources.items():
                        mul = GF_MUL[cauchy(r, j)]
                        for t in range(L):
                            y[t] ^= mul[sj[t]]
                    rhs.append(y)
                solved = solve_gf([[cauchy(r, j) for j in missing] for r, _ in rows], rhs)
                for j, symbol in zip(missing, solved):
                    for t in span(j):
                        have[t] = symbol[t - j * L]
                c["recovered"] = True
        if len(have) < size:
            return True
        coded = bytes(have[t] for t in range(size))
        c["have"], c["rows"] = {}, []
        if crc32c(coded) != crc:
            c["recovered"] = False  # discarded: none received, no row held
            return False
        c["complete"], c["coded"] = True, coded
        return True

    def repair(self, obj, h, offset):
        """Spec 17.3 (steps 13..15) and 17.4, once the object's entry has arrived."""
        p = h["payload"]
        first, batch, k, row = repair_fields(p)
        info = obj["info"]
        if len(p) != 8 + (batch * record_bits(self.info, info) + 7) // 8:
            return self.reject(offset, "malformed payload")
        if first + (k - 1) * batch >= info["point_count"]:
            return self.reject(offset, "index out of range")
        count = min(first + k * batch, info["point_count"]) - first  # the block's range, cut at the last point
        block = obj["blocks"].get(first)
        if block is not None:
            if (block["batch"], block["k"]) != (batch, k):
                return self.reject(offset, "stream mismatch")
        else:
            for other in obj["blocks"].values():
                if other["first"] < first + count and first < other["first"] + other["count"]:
                    return self.reject(offset, "stream mismatch")
            block = obj["blocks"][first] = dict(first=first, batch=batch, k=k, count=count, rows=[], recovered=False,
                                                points_recovered=0)
        if self.complete(obj, block) or row in [r for r, _ in block["rows"]]:
            self.counters["duplicates"] += 1
            return "duplicate"
        block["rows"].append((row, p[8:]))
        self.counters["accepted"] += 1
        self.recover(obj, block)
        return "accepted"

    def batch_range(self, block, i):
        start = block["first"] + i * block["batch"]
        return range(start, min(start + block["batch"], block["first"] + block["count"]))

    def complete(self, obj, block):
        held = self.held_store(obj)  # for a mapped object: every record held, placed or not (23.6)
        return all(i in held for i in range(block["first"], block["first"] + block["count"]))

    def recover(self, obj, block):
        """Spec 17.4: with u batches not wholly held and at least u rows, solve with the first u rows."""
        if block["recovered"] or self.complete(obj, block):
            return
        points, k = self.held_store(obj), block["k"]
        known = [j for j in range(k) if all(i in points for i in self.batch_range(block, j))]
        unknown = [j for j in range(k) if j not in known]
        u = len(unknown)
        if len(block["rows"]) < u:
            return
        widths = record_widths(self.info, obj["info"])
        length = (block["batch"] * sum(widths) + 7) // 8
        sources = {j: pack_records([points[i] for i in self.batch_range(block, j)], widths, length) for j in known}
        rows = block["rows"][:u]
        rhs = []
        for r, symbol in rows:
            y = bytearray(symbol)
            for j, s in sources.items():
                mul = GF_MUL[cauchy(r, j)]
                for t in range(length):
                    y[t] ^= mul[s[t]]
            rhs.append(y)
        solved = solve_gf([[cauchy(r, j) for j in unknown] for r, _ in rows], rhs)
        for j, symbol in zip(unknown, solved):
            bits = Bits(symbol)
            for i in self.batch_range(block, j):
                q = [bits.get(n) for n in widths]
                if i not in points:  # points held are kept (the first copy, spec 7.2)
                    if obj["info"]["map_level"]:
                        self.take_record(obj, i, q)  # as if a MAPPED_POINTS packet had brought it (23.5)
                    else:
                        points[i] = q
                    block["points_recovered"] += 1
                    obj["recovered"] += 1
        block["recovered"] = True

    def camera_light(self, h, offset):
        """Spec 26.2 / 26.3: the checks, then the table size, then the record against the one held (floats as
        numbers, the name as bytes); the first of an index is accepted, an identical one a duplicate."""
        camera = h["type"] == 0x17
        d = (decode_camera if camera else decode_light)(h["payload"])
        if d is None:
            return self.reject(offset, "malformed payload")
        count = self.camera_count if camera else self.light_count
        table = self.cameras if camera else self.lights
        if count is not None and d["count"] != count:
            return self.reject(offset, "stream mismatch")
        if d["index"] in table:
            if table[d["index"]] != d:  # Python's float equality: +0 == -0
                return self.reject(offset, "stream mismatch")
            return self.news(False)
        table[d["index"]] = d
        if camera:
            self.camera_count = d["count"]
        else:
            self.light_count = d["count"]
        return self.news(True)

    def extras(self, h, offset):
        """Spec 28.1: rules 1..5, then checks 1..6 in their order; bytes kept by offset, the first copy of each."""
        p = h["payload"]
        if len(p) < 21:
            return self.reject(offset, "malformed payload")
        kind, index, count, size, crc, at = p[0], struct.unpack_from("<H", p, 2)[0], struct.unpack_from("<H", p, 4)[0], \
            *struct.unpack_from("<III", p, 8)
        data = p[20:]
        if kind > 10 or (kind in (0, 1) and index != 0) or count == 0 or size == 0 or size > 65536 \
                or at + len(data) > size:
            return self.reject(offset, "malformed payload")
        if self.extras_count is not None and count != self.extras_count:
            return self.reject(offset, "stream mismatch")  # check 1
        key = (kind, index)
        t = self.texts.get(key)
        if t is not None:
            if (t["size"], t["crc"]) != (size, crc):
                return self.reject(offset, "stream mismatch")  # check 2: the description
            if t["complete"]:
                return self.news(False)  # check 3
        elif len(self.texts) >= count:
            return self.reject(offset, "stream mismatch")  # check 2: one target more than text_count
        got = t["got"] if t is not None else [False] * size
        fresh = [k for k in range(len(data)) if not got[at + k]]
        if not fresh:
            return self.news(False)  # check 3 (check 4, the memory cap, no vector reaches)
        if t is None:
            t = self.texts[key] = dict(size=size, crc=crc, have=bytearray(size), got=got, received=0,
                                       complete=False, text=None)
            self.extras_count = count
        for k in fresh:
            t["got"][at + k] = True
            t["have"][at + k] = data[k]
        t["received"] += len(fresh)
        if t["received"] == size:
            whole = bytes(t["have"])
            t["got"], t["have"], t["received"] = [False] * size, bytearray(size), 0  # discarded unless both pass
            if crc32c(whole) != crc:
                return self.reject(offset, "stream mismatch")  # check 5
            try:
                PatchReader(whole.decode("utf-8")).document()  # rules 2..7 of 18.2 on any value
            except (UnicodeDecodeError, PatchError):
                return self.reject(offset, "malformed payload")  # check 6
            t["complete"], t["text"], t["received"] = True, whole.decode("utf-8"), size
        return self.news(True)

    def required_extension(self, h, offset):
        """Spec 29.1: rules 1..3, then comparisons 1..3."""
        p = h["payload"]
        if not 5 <= len(p) <= 68 or p[0] == 0 or p[1] >= p[0] or any(b not in NAME_BYTES for b in p[4:]):
            return self.reject(offset, "malformed payload")
        count, index, name = p[0], p[1], bytes(p[4:]).decode("ascii")
        if self.name_count is not None and count != self.name_count:
            return self.reject(offset, "stream mismatch")  # comparison 1
        if index in self.names:
            return self.news(False) if self.names[index] == name else self.reject(offset, "stream mismatch")  # 2
        if name in self.names.values():
            return self.reject(offset, "stream mismatch")  # comparison 3
        self.name_count = count
        self.names[index] = name
        return self.news(True)

    def extras_json(self):
        return [dict(kind=EXTRAS_KINDS[k], index=i, text_size=t["size"], text_crc=t["crc"],
                     received_bytes=t["received"], complete=t["complete"], text=t["text"])
                for (k, i), t in sorted(self.texts.items())]

    def cameras_lights_json(self):
        cameras, lights = [], []
        for k in sorted(self.cameras):
            c = self.cameras[k]
            persp = c["projection"] == 0
            cameras.append({"index": k, "name": c["name"].decode("utf-8", errors="replace"),
                            "projection": "perspective" if persp else "orthographic",
                            ("aspect_ratio" if persp else "xmag"): c["a"], ("yfov" if persp else "ymag"): c["b"],
                            "znear": c["znear"], "zfar": c["zfar"]})
        for k in sorted(self.lights):
            l = self.lights[k]
            lights.append(dict(index=k, name=l["name"].decode("utf-8", errors="replace"),
                               type=("directional", "point", "spot")[l["type"]], color=l["color"],
                               intensity=l["intensity"], range=l["range"], inner_cone_angle=l["inner"],
                               outer_cone_angle=l["outer"]))
        return dict(camera_count=self.camera_count, cameras=cameras, light_count=self.light_count, lights=lights)

    def news(self, fresh):
        self.counters["accepted" if fresh else "duplicates"] += 1
        return "accepted" if fresh else "duplicate"

    def scene(self, h, offset):
        """Spec 15.1."""
        d = decode_scene(h["payload"], h["minor"])
        if d is None:
            return self.reject(offset, "malformed payload")
        counts, nodes, meshes = d
        # Spec 15.1: table sizes 0 and 0 fix nothing; the sizes of a taken SCENE packet bind the later
        # ones only when one of them is not 0.
        if self.scene_counts not in (None, (0, 0)) and counts != self.scene_counts:
            return self.reject(offset, "stream mismatch")
        for table, records in ((self.nodes, nodes), (self.meshes, meshes)):
            for r in records:
                if r["index"] in table and table[r["index"]] != r:
                    return self.reject(offset, "stream mismatch")
        self.scene_counts = counts
        fresh = False
        for table, records in ((self.nodes, nodes), (self.meshes, meshes)):
            for r in records:
                if r["index"] not in table:
                    table[r["index"]] = r
                    fresh = True
        return self.news(fresh)

    def material(self, h, offset):
        """Spec 15.2."""
        m = decode_material(h["payload"])
        if m is None:
            return self.reject(offset, "malformed payload")
        count = m.pop("material_count")
        if self.material_count is not None and count != self.material_count:  # materials and patches (18.2)
            return self.reject(offset, "stream mismatch")
        if m["index"] in self.materials:
            if self.materials[m["index"]] != m:
                return self.reject(offset, "stream mismatch")
            return self.news(False)
        self.material_count = count
        self.materials[m["index"]] = m
        return self.news(True)

    def extensions(self, h, offset):
        """Spec 18.2: the payload, the table size, then the patch held for the same material."""
        p = h["payload"]
        if len(p) < 6:
            return self.reject(offset, "malformed payload")
        index, count = struct.unpack_from("<HH", p, 0)
        refs = check_patch(p[4:]) if index < count else None
        if refs is None:
            return self.reject(offset, "malformed payload")
        if self.material_count is not None and count != self.material_count:
            return self.reject(offset, "stream mismatch")
        if index in self.patches:
            if self.patches[index][0] != p[4:]:
                return self.reject(offset, "stream mismatch")
            return self.news(False)
        self.material_count = count
        self.patches[index] = (p[4:], refs)
        return self.news(True)

    def fragment(self, h, offset):
        """Spec 15.3: pieces keyed by byte offset; complete once every byte arrived and the CRC matches."""
        p = h["payload"]
        if len(p) <= 28:
            return self.reject(offset, "malformed payload")
        index, count, itype = struct.unpack_from("<HHB", p, 0)
        sampler = list(struct.unpack_from("<4H", p, 6))
        size, crc, at = struct.unpack_from("<III", p, 16)
        data = p[28:]
        if index >= count or itype not in (1, 2) or at + len(data) > size:
            return self.reject(offset, "malformed payload")
        desc = dict(index=index, texture_count=count, image_type=itype, sampler=sampler, image_size=size, image_crc=crc)
        if self.textures and count != next(iter(self.textures.values()))["desc"]["texture_count"]:
            return self.reject(offset, "stream mismatch")
        t = self.textures.setdefault(index, dict(desc=desc, have=bytearray(size), got=[False] * size,
                                                 received=0, complete=False, image=None))
        if t["desc"] != desc:
            return self.reject(offset, "stream mismatch")
        if t["complete"]:
            return self.news(False)
        fresh = 0
        for k, b in enumerate(data):
            if not t["got"][at + k]:  # the first copy of a byte is kept
                t["got"][at + k] = True
                t["have"][at + k] = b
                fresh += 1
        if not fresh:
            return self.news(False)
        t["received"] += fresh
        if t["received"] == size:
            if crc32c(t["have"]) != crc:
                t["got"], t["received"] = [False] * size, 0
                return self.reject(offset, "stream mismatch")
            t["complete"], t["image"] = True, bytes(t["have"])
        return self.news(True)

    def animation(self, h, offset):
        """Spec 20.1: the packet's checks, then the comparisons in their order; keys are kept by index."""
        p = h["payload"]
        if len(p) < 24:
            return self.reject(offset, "malformed payload")
        index, table, track, track_count, node, path, interp, key_count, first, count, name_length = \
            struct.unpack_from("<HHHHHBBIIHB", p, 0)
        if path > 2 or interp > 2:
            return self.reject(offset, "malformed payload")
        c = 4 if path == 1 else 3  # a rotation is a quaternion x, y, z, w
        v = 3 * c if interp == 2 else c  # a cubic spline key: in-tangent, value, out-tangent
        # Python integers do not overflow: first + count is the true sum.
        if len(p) != 24 + name_length + count * 4 * (1 + v) or index >= table or track >= track_count \
                or key_count == 0 or (interp == 2 and key_count < 2) or count == 0 or first + count > key_count:
            return self.reject(offset, "malformed payload")
        name = p[24:24 + name_length]
        keys = []  # each (time, value 1, .., value V)
        for k in range(count):
            key = struct.unpack_from("<%df" % (1 + v), p, 24 + name_length + 4 * (1 + v) * k)
            # -0.0 < 0 is false in Python as in IEEE 754: a time of -0 is not negative.
            if not finite(key) or key[0] < 0 or (keys and not key[0] > keys[-1][0]):
                return self.reject(offset, "malformed payload")
            keys.append(key)
        if self.animation_count is not None and table != self.animation_count:
            return self.reject(offset, "stream mismatch")
        a = self.animations.get(index)
        if a is not None and (a["track_count"] != track_count or a["name"] != name):  # names as bytes
            return self.reject(offset, "stream mismatch")
        t = a["tracks"].get(track) if a is not None else None
        desc = (node, path, interp, key_count)
        if t is not None and t["desc"] != desc:
            return self.reject(offset, "stream mismatch")
        held = t["keys"] if t is not None else {}
        # Keys compare as numbers: Python's float equality has +0 == -0 (and no NaN got this far).
        if any(first + k in held and held[first + k] != key for k, key in enumerate(keys)):
            return self.reject(offset, "stream mismatch")
        fresh = [k for k in range(count) if first + k not in held]
        if not fresh:
            return self.news(False)
        self.animation_count = table
        if a is None:
            a = self.animations[index] = dict(track_count=track_count, name=name, tracks={})
        if t is None:
            t = a["tracks"][track] = dict(desc=desc, keys={})
        for k in fresh:
            t["keys"][first + k] = keys[k]
        return self.news(True)

    def morph_animation(self, h, offset):
        """Spec 22.2: the packet's checks, then the comparisons in their order (as for ANIMATION, 20.1); keys
        are kept by index."""
        d = decode_morph_animation(h["payload"])
        if d is None:
            return self.reject(offset, "malformed payload")
        index, table, track, track_count, joins, name, desc, first, keys = d
        if self.morph_count is not None and table != self.morph_count:
            return self.reject(offset, "stream mismatch")
        a = self.morphs.get(index)
        if a is not None and (a["track_count"], a["joins"], a["name"]) != (track_count, joins, name):
            return self.reject(offset, "stream mismatch")
        t = a["tracks"].get(track) if a is not None else None
        if t is not None and t["desc"] != desc:
            return self.reject(offset, "stream mismatch")
        held = t["keys"] if t is not None else {}
        if any(first + k in held and held[first + k] != key for k, key in enumerate(keys)):
            return self.reject(offset, "stream mismatch")
        fresh = [k for k in range(len(keys)) if first + k not in held]
        if not fresh:
            return self.news(False)
        self.morph_count = table
        if a is None:
            a = self.morphs[index] = dict(track_count=track_count, joins=joins, name=name, tracks={})
        if t is None:
            t = a["tracks"][track] = dict(desc=desc, keys={})
        for k in fresh:
            t["keys"][first + k] = keys[k]
        return self.news(True)

    def skin(self, h, offset):
        """Spec 21.1: the packet's checks, then the comparisons in their order; joints are kept by index."""
        d = decode_skin(h["payload"])
        if d is None:
            return self.reject(offset, "malformed payload")
        index, table, joint_count, first, skeleton, name, joints = d
        if self.skin_count is not None and table != self.skin_count:
            return self.reject(offset, "stream mismatch")
        k = self.skins.get(index)
        if k is not None and (k["joint_count"], k["skeleton"], k["name"]) != (joint_count, skeleton, name):
            return self.reject(offset, "stream mismatch")
        held = k["joints"] if k is not None else {}
        # Matrix entries compare as numbers: Python's float equality has +0 == -0 (and no NaN got this far).
        if any(first + i in held and held[first + i] != j for i, j in enumerate(joints)):
            return self.reject(offset, "stream mismatch")
        fresh = [i for i in range(len(joints)) if first + i not in held]
        if not fresh:
            return self.news(False)
        self.skin_count = table
        if k is None:
            k = self.skins[index] = dict(joint_count=joint_count, skeleton=skeleton, name=name, joints={})
        for i in fresh:
            k["joints"][first + i] = joints[i]
        return self.news(True)

    def skins_json(self):
        out = []
        for index in sorted(self.skins):
            k = self.skins[index]
            missing, cursor = [], 0
            for j in sorted(k["joints"]):
                if j > cursor:
                    missing.append([cursor, j])
                cursor = j + 1
            if cursor < k["joint_count"]:
                missing.append([cursor, k["joint_count"]])
            out.append(dict(index=index, name=k["name"].decode("utf-8", errors="replace"), joint_count=k["joint_count"],
                            skeleton=None if k["skeleton"] == NONE else k["skeleton"], joints_held=len(k["joints"]),
                            missing=missing, complete=len(k["joints"]) == k["joint_count"],
                            joints=[dict(index=j, node=k["joints"][j][0], matrix=k["joints"][j][1])
                                    for j in sorted(k["joints"])]))
        return out

    def skinned(self, shown_nodes):
        """Spec 21.3: the shown nodes (in order) shown skinned, each {node, skin}."""
        def arrived(o):  # spec 15.4: its entry and at least one element of it
            return o < len(self.objects) and self.objects[o]["info"] is not None and \
                bool(self.objects[o]["ellipsoids"] or self.objects[o]["points"])

        def weighted(o):  # a point held together with its record
            return any(i in self.objects[o]["points"] for i in self.objects[o]["weights"])
        out = []
        for index in shown_nodes:
            n = self.nodes[index]
            k = self.skins.get(n["skin"])
            if k is None or len(k["joints"]) != k["joint_count"]:
                continue
            if (k["skeleton"] != NONE and k["skeleton"] not in shown_nodes) or \
                    any(node not in shown_nodes for node, _ in k["joints"].values()):
                continue
            if n["mesh"] not in self.meshes:
                continue
            objects = [p["object"] for p in self.meshes[n["mesh"]]["primitives"] if arrived(p["object"])]
            if objects and all(weighted(o) and all(j < k["joint_count"] for joints, _ in self.objects[o]["weights"].values()
                                                   for j in joints) for o in objects):
                out.append(dict(node=index, skin=n["skin"]))
        return out

    @staticmethod
    def track_state(t):
        """Spec 20.2: (complete, usable, times, values) of a track; times and values None until complete."""
        key_count, keys = t["desc"][3], t["keys"]
        if len(keys) < key_count:
            return False, False, None, None
        times = [keys[i][0] for i in range(key_count)]
        values = [x for i in range(key_count) for x in keys[i][1:]]
        return True, all(a < b for a, b in zip(times, times[1:])), times, values

    def animation_complete(self, a):
        return len(a["tracks"]) == a["track_count"] and all(self.track_state(t)[0] for t in a["tracks"].values())

    def animations_json(self, morph=False):
        """The ANIMATION table (spec 20), or with `morph` the morph animation table (spec 22.2), whose tracks
        have a target count in place of a path and whose animations say what they join."""
        out = []
        table = self.morphs if morph else self.animations
        for k in sorted(table):
            a = table[k]
            tracks = []
            for i in sorted(a["tracks"]):
                t = a["tracks"][i]
                node, path, interp, key_count = t["desc"]  # for a morph track, `path` is its target count C
                complete, usable, times, values = self.track_state(t)
                missing, cursor = [], 0
                if not complete:
                    for key in sorted(t["keys"]):
                        if key > cursor:
                            missing.append([cursor, key])
                        cursor = key + 1
                    if cursor < key_count:
                        missing.append([cursor, key_count])
                track = dict(index=i, node=node, interpolation=INTERPOLATIONS[interp], key_count=key_count,
                             keys_held=len(t["keys"]), missing=missing, complete=complete, usable=usable, times=times,
                             values=values)
                if morph:
                    track["target_count"] = path
                else:
                    track["path"] = PATHS[path]
                tracks.append(track)
            entry = dict(index=k, name=a["name"].decode("utf-8", errors="replace"), track_count=a["track_count"],
                         complete=self.animation_complete(a), tracks=tracks)
            if morph:
                entry["joins"] = None if a["joins"] == NONE else a["joins"]
            out.append(entry)
        return out

    def object_arrived(self, o):
        """Spec 15.4: an object has arrived with its entry and at least one element of it."""
        return o < len(self.objects) and self.objects[o]["info"] is not None and \
            bool(self.objects[o]["ellipsoids"] or self.objects[o]["points"])

    def shown_with_targets(self, mesh):
        """Spec 22.4: a mesh record with target_count > 0 that is shown (15.4: at least one of its objects has
        arrived) and every arrived object of which is morphed (22.3: a point held together with its record)
        with that target_count (the one kept for the object, 22.1)."""
        targets = len(mesh["weights"])
        objects = [p["object"] for p in mesh["primitives"] if self.object_arrived(p["object"])]
        return targets > 0 and bool(objects) and all(
            self.objects[o]["morph_kind"] is not None and self.objects[o]["morph_kind"][0] == targets and
            any(i in self.objects[o]["points"] for i in self.objects[o]["morph"]) for o in objects)

    def shown_animations(self, shown_nodes):
        """Spec 20.2 and 22.4: each complete animation with its usable tracks over shown nodes, one per node and
        path (the first kept), and the kept tracks of the complete morph animations that join it; then the
        complete morph animations that stand alone. An animation left without a track is not shown."""
        def node_targets(node):  # the target count of the node's mesh when it is shown with its targets, else 0
            mesh = self.meshes.get(self.nodes[node]["mesh"]) if node in self.nodes else None
            return len(mesh["weights"]) if mesh is not None and self.shown_with_targets(mesh) else 0

        def morph_tracks(indices):
            """The kept tracks of morph animations `indices` (in that order, then track order), written into one
            animation: usable, on a shown node whose mesh is shown with the track's C targets, one per node."""
            kept, nodes = [], set()
            for m in indices:
                for i in sorted(self.morphs[m]["tracks"]):
                    t = self.morphs[m]["tracks"][i]
                    node, c = t["desc"][0], t["desc"][1]
                    if not self.track_state(t)[1] or node not in shown_nodes or node_targets(node) != c \
                            or node in nodes:
                        continue
                    nodes.add(node)
                    kept.append([m, i])
            return kept

        # Once a MORPH_ANIMATION packet was taken, an animation of A waits until every morph animation of the
        # morph table has taken a packet and those that join it are complete (spec 22.4).
        table_known = self.morph_count is None or all(m in self.morphs for m in range(self.morph_count))
        out = []
        for k in sorted(self.animations):
            a = self.animations[k]
            joining = [m for m in sorted(self.morphs) if self.morphs[m]["joins"] == k]
            if not self.animation_complete(a) or not table_known or \
                    not all(self.animation_complete(self.morphs[m]) for m in joining):
                continue
            kept, targets = [], set()
            for i in sorted(a["tracks"]):
                t = a["tracks"][i]
                node, path = t["desc"][0], t["desc"][1]
                if not self.track_state(t)[1] or node not in shown_nodes or (node, path) in targets:
                    continue
                targets.add((node, path))
                kept.append(i)
            morphs = morph_tracks(joining)
            if kept or morphs:
                out.append(dict(index=k, tracks=kept, morph_only=False, morph_tracks=morphs))
        for m in sorted(self.morphs):
            if self.morphs[m]["joins"] == NONE and self.animation_complete(self.morphs[m]):
                morphs = morph_tracks([m])
                if morphs:
                    out.append(dict(index=m, tracks=[], morph_only=True, morph_tracks=morphs))
        return out

    def scene_json(self, viewed=False, with_extras=False, with_required=False):
        nodes = [self.nodes[k] for k in sorted(self.nodes)]
        meshes = [self.meshes[k] for k in sorted(self.meshes)]
        textures = []
        for k in sorted(self.textures):
            t = self.textures[k]
            d = t["desc"]
            missing, run = [], None
            for i, g in enumerate(t["got"]):
                if not g and run is None:
                    run = i
                elif g and run is not None:
                    missing.append([run, i])
                    run = None
            if run is not None:
                missing.append([run, d["image_size"]])
            textures.append(dict(index=k, image_type="PNG" if d["image_type"] == 1 else "JPEG", sampler=d["sampler"],
                                 image_size=d["image_size"], image_crc=d["image_crc"], received_bytes=t["received"],
                                 missing=[] if t["complete"] else missing, complete=t["complete"],
                                 image_digest=fnv_bytes(t["image"]) if t["complete"] else None))
        sized = self.scene_counts not in (None, (0, 0))  # sizes 0 and 0 are listed as null (README)
        return dict(node_count=self.scene_counts[0] if sized else None,
                    mesh_count=self.scene_counts[1] if sized else None,
                    nodes=[node_json(n, viewed) for n in nodes],
                    meshes=[dict(m, primitives=[dict(object=q["object"], material=None if q["material"] == NONE
                                                     else q["material"]) for q in m["primitives"]]) for m in meshes],
                    material_count=self.material_count,
                    materials=[material_json(self.materials[k]) for k in sorted(self.materials)],
                    material_extensions=[dict(index=k, patch=self.patches[k][0].decode("utf-8"),
                                              references=self.patches[k][1]) for k in sorted(self.patches)],
                    texture_count=self.textures[min(self.textures)]["desc"]["texture_count"] if self.textures else None,
                    textures=textures, animation_count=self.animation_count, animations=self.animations_json(),
                    skin_count=self.skin_count, skins=self.skins_json(), morph_animation_count=self.morph_count,
                    morph_animations=self.animations_json(morph=True), shown=self.shown(viewed),
                    **(self.cameras_lights_json() if viewed else {}),
                    **(dict(extras_count=self.extras_count, extras=self.extras_json()) if with_extras else {}),
                    **(dict(required_extension_count=self.name_count,
                            required_extensions=[dict(index=k, name=self.names[k]) for k in sorted(self.names)])
                       if with_required else {}))

    def shown(self, viewed=False):
        """Spec 15.4 and 18.4: what a receiver shows (and spec 26.4: the cameras and lights on shown nodes)."""
        done = [k for k in sorted(self.textures) if self.textures[k]["complete"]]
        materials, waiting, ignored, waiting_extensions = [], [], [], []
        for k in sorted(self.materials):
            needs = []  # (slot, texture): the core references on set 0, then the patch's (18.3)
            for slot, ref in zip(SLOTS, self.materials[k]["refs"]):
                texture, texcoord, _ = ref
                if texture == NONE:
                    continue
                if texcoord != 0:
                    ignored.append(dict(material=k, slot=slot, texcoord=texcoord))
                    continue
                needs.append((slot, texture))
            ok = True
            if k in self.patches:  # applied once it arrived, whatever the bit says (18.4)
                needs += [(r["path"], r["texture"]) for r in self.patches[k][1]]
            elif self.materials[k]["has_extensions"]:
                ok = False
                waiting_extensions.append(k)
            for slot, texture in needs:
                if texture in done:
                    continue
                ok = False
                t = self.textures.get(texture)
                waiting.append(dict(material=k, slot=slot, texture=texture, received_bytes=t["received"] if t else 0,
                                    image_size=t["desc"]["image_size"] if t else None))
            if ok:
                materials.append(k)
        nodes = []
        for k in sorted(self.nodes):
            at, seen, reaches = k, set(), False
            while at in self.nodes and at not in seen:
                seen.add(at)
                if self.nodes[at]["parent"] == NONE:
                    reaches = True
                    break
                at = self.nodes[at]["parent"]
            if reaches:
                mesh = self.nodes[k]["mesh"]
                nodes.append(dict(index=k, mesh=mesh if mesh != NONE and mesh in self.meshes else None))
        shown_nodes = [n["index"] for n in nodes]
        out = dict(textures=done, materials=materials, waiting=waiting, waiting_extensions=waiting_extensions,
                   ignored_references=ignored, nodes=nodes, animations=self.shown_animations(set(shown_nodes)),
                   skinned=self.skinned(shown_nodes),
                   morphed=[k for k in sorted(self.meshes) if self.shown_with_targets(self.meshes[k])])
        if viewed:
            with_camera, with_light, waiting_view = [], [], []
            for k in shown_nodes:
                camera, light = self.nodes[k]["camera"], self.nodes[k]["light"]
                if camera != NONE:
                    (with_camera if camera in self.cameras else waiting_view).append(dict(node=k, camera=camera))
                if light != NONE:
                    (with_light if light in self.lights else waiting_view).append(dict(node=k, light=light))
            out.update(node_cameras=with_camera, node_lights=with_light, waiting_cameras_lights=waiting_view)
        return out


class RangeDecoder:
    """Spec 19.3: LZMA's binary range decoder; a byte past the end reads as 0."""

    def __init__(self, data):
        self.data, self.pos = data, 0
        self.range, self.code = 0xFFFFFFFF, 0
        for _ in range(5):
            self.code = (self.code * 256 + self.byte()) % 2 ** 32

    def byte(self):
        b = self.data[self.pos] if self.pos < len(self.data) else 0
        self.pos += 1
        return b

    def normalize(self):
        if self.range < 2 ** 24:
            self.range = (self.range * 256) % 2 ** 32
            self.code = (self.code * 256 + self.byte()) % 2 ** 32

    def bit(self, probs, k):
        p = probs[k]
        bound = (self.range >> 11) * p
        if self.code < bound:
            self.range = bound
            probs[k] = p + ((2048 - p) >> 5)
            b = 0
        else:
            self.range -= bound
            self.code -= bound
            probs[k] = p - (p >> 5)
            b = 1
        self.normalize()
        return b

    def direct(self, bits):
        v = 0
        for _ in range(bits):
            self.range >>= 1
            b = 0
            if self.code >= self.range:
                self.code -= self.range
                b = 1
            self.normalize()
            v = v * 2 + b
        return v


# The contexts of spec 19.3 and 27.2, one list per object, each probability starting at 1024: `none`, `rank 1` ..
# `rank 16` (19.3), then (27.2) `fresh 0` .. `fresh 2` (by the gate's local candidates: none, one, more; a seed's
# corners `fresh 0`), ten sets of `length 0` .. `length 17` (set 0 for a displacement's x, 1 + min(c', 8) for y and
# z, c' the bit length read for the axis before), `sign`, and for texture coordinates ten sets of `uv length 0` ..
# `uv length 17` and `uv sign`.
CTX_NONE, CTX_RANK, CTX_FRESH, CTX_LENGTH, CTX_SIGN, CTX_UV_LENGTH, CTX_UV_SIGN = 0, 1, 17, 20, 200, 201, 381
CTX_COUNT = 382


class Unusable(Exception):
    """The coded connectivity or coded mesh is unusable (spec 19.2, 27.2)."""


def decode_connectivity(coded, triangle_count, positions, carried_count=0, position_bits=16, attribute_widths=(),
                        stats=None, texcoords=None, attributes=0):
    """Spec 27.2 (EXACT_MESH), of which spec 19.2 (CONNECTIVITY) is the case carried_count M = 0: no `fresh` bit is
    read, every neighbour list stays empty, no vertex is carried, and w is the bit count of n - 1. `positions`: the quantized positions
    of the points 0 .. n - 1; `position_bits`: the stream's P; `attribute_widths`: the bit widths of the fields of a
    POINTS record after the position (spec 7.1), and `attributes` the object's attribute bits; `texcoords`: the
    points' quantized texture coordinates (None: the object has none). Returns (T, carried), the exact triangle list over vertices (points
    0 .. n - 1, then carried vertices n .. n + M - 1) and each carried vertex's integers (position, then attributes,
    as a point's), or None when the connectivity is unusable. The candidates of a gate (the points and its local
    candidates) are found by sorting them all (fine for small objects). `stats`, when given, counts what the decode
    met: seeds, skipped gates, none bits, each rank, explicit indices, fresh vertices."""
    n, M = len(positions), carried_count
    w = max(1, (n + M - 1).bit_length())
    rc = RangeDecoder(coded)
    probs = [1024] * CTX_COUNT
    P = [list(p) for p in positions]  # the quantized position of every known vertex
    TC = [list(t) for t in texcoords] if texcoords is not None else [[0, 0] for _ in positions]  # and texcoords
    carried = []
    C = {}  # vertex -> its neighbour list C(v) (27.2), absent while empty
    T, D, Q = [], set(), []
    head = 0
    count = lambda key: stats is not None and stats.__setitem__(key, stats.get(key, 0) + 1)

    def take(a, b, c):
        T.append([a, b, c])
        D.update(((a, b), (b, c), (c, a)))
        Q.extend(((a, b, c), (b, c, a), (c, a, b)))
        if M:
            for u, v in ((a, b), (b, c), (c, a)):
                for s, t in ((u, v), (v, u)):
                    lst = C.setdefault(s, [])
                    if t >= n and t not in lst and len(lst) < 16:
                        lst.append(t)

    def displacement(length_base, sign, components):
        d = []
        lengths = length_base
        for _ in range(components):
            c = next((c for c in range(18) if rc.bit(probs, lengths + c)), None)
            if c is None:
                raise Unusable
            lengths = length_base + 18 * (1 + min(c, 8))
            if c == 0:
                d.append(0)
                continue
            negative = rc.bit(probs, sign)
            v = (1 << (c - 1)) + rc.direct(c - 1)
            d.append(-v if negative else v)
        return d

    def fresh(R, U):
        d = displacement(CTX_LENGTH, CTX_SIGN, 3)
        p = [R[k] + d[k] for k in range(3)]
        if any(not 0 <= v < 1 << position_bits for v in p):
            raise Unusable
        fields, uv, widths = [], [0, 0], list(attribute_widths)
        if attributes & 1:  # the normal: direct bits
            fields += [rc.direct(b) for b in widths[:2]]
            widths = widths[2:]
        if attributes & 2:  # the texture coordinates: a displacement from U
            e = displacement(CTX_UV_LENGTH, CTX_UV_SIGN, 2)
            uv = [U[k] + e[k] for k in range(2)]
            if any(not 0 <= v < 1 << widths[0] for v in uv):
                raise Unusable
            fields += uv
            widths = widths[2:]
        fields += [rc.direct(b) for b in widths]  # the colour: direct bits
        carried.append(p + fields)
        P.append(p)
        TC.append(uv)
        count("fresh")
        return n + len(carried) - 1

    dist = lambda v, R: sum((P[v][k] - R[k]) ** 2 for k in range(3))
    try:
        while len(T) < triangle_count:
            if head == len(Q):
                corners = []
                for k in range(3):
                    if len(carried) < M and rc.bit(probs, CTX_FRESH):  # `fresh 0`
                        if corners:
                            R, U = P[corners[-1]], TC[corners[-1]]
                        else:
                            R = [1 << (position_bits - 1)] * 3
                            U = [1 << (attribute_widths[2 if attributes & 1 else 0] - 1)] * 2 if attributes & 2 else [0, 0]
                        corners.append(fresh(R, U))
                    else:
                        x = rc.direct(w)
                        if x >= n + len(carried) or x in corners:
                            raise Unusable
                        corners.append(x)
                count("seeds")
                take(*corners)
                continue
            a, b, o = Q[head]
            head += 1
            if (b, a) in D:
                count("gates decoded before")
                continue
            if rc.bit(probs, CTX_NONE):
                count("none")
                continue
            R = [P[a][k] + P[b][k] - P[o][k] for k in range(3)]
            local = []
            for v in C.get(a, []) + C.get(b, []):
                if v not in (a, b) and v not in local:
                    local.append(v)
            local.sort(key=lambda v: (dist(v, R), v))
            if len(carried) < M and rc.bit(probs, CTX_FRESH + min(len(local), 2)):
                take(b, a, fresh(R, [TC[a][k] + TC[b][k] - TC[o][k] for k in range(2)]))
                continue
            rank = next((r for r in range(1, 17) if rc.bit(probs, CTX_RANK + r - 1)), 0)
            if rank:
                # 27.2 step 4: the points other than a and b, and the local candidates, together.
                order = sorted([(dist(i, R), i) for i in range(n) if i not in (a, b)] + [(dist(v, R), v) for v in local])
                if len(order) < rank:
                    raise Unusable
                x = order[rank - 1][1]
                count("rank %d" % rank)
            else:
                x = rc.direct(w)
                if x >= n + len(carried) or x in (a, b):
                    raise Unusable
                count("explicit index")
            take(b, a, x)
    except Unusable:
        return None
    if len(carried) < M:  # a carried vertex that no triangle uses
        return None
    return T, carried


def exact_layer(obj, info):
    """Spec 19.4, 27.3: (the exact triangle list over vertices, the carried vertices' integers) of an object that is
    exact (every point held, its exact layer complete and decoded without being unusable), else None. `info`: the
    stream-level fields."""
    c = obj.get("connectivity")
    if c is None or not c["complete"] or len(obj["points"]) != obj["info"]["point_count"]:
        return None
    count, carried, _, _ = c["desc"]
    positions = [obj["points"][i][:3] for i in range(obj["info"]["point_count"])]
    widths = record_widths(info, dict(obj["info"], map_level=0))[3:]  # a POINTS record's fields after the position
    a = obj["info"]["attributes"]
    texcoords = None
    if a & 2:
        at = 3 + (2 if a & 1 else 0)
        texcoords = [obj["points"][i][at:at + 2] for i in range(obj["info"]["point_count"])]
    return decode_connectivity(c["coded"], count, positions, carried, info["position_bits"], widths,
                               texcoords=texcoords, attributes=a)


def normals_json(obj, info):
    """Spec 24.2..24.4: the entries held (by index), whether they are complete, and, for an exact object, every
    point's surface normal over its exact triangle list (null where undefined). (An object with surface normals has
    no carried vertex, spec 27.1; were there any, they would take part in the sums and not be listed.)"""
    bits = info["normal_bits"]
    entries = []
    for i, e in sorted(obj["normals"].items()):
        if e is None:
            entries.append(dict(index=i, sent=False))
        else:
            entries.append(dict(index=i, sent=True, q=list(e), normal=decode_octahedral(e[0], e[1], bits)))
    surface = None
    layer = exact_layer(obj, info)
    if layer is not None:
        triangles, carried = layer
        n = obj["info"]["point_count"]
        positions = [obj["points"][i][:3] for i in range(n)] + [q[:3] for q in carried]
        # Every vertex of the exact triangle list: the points, then (format 1.11) the carried vertices.
        surface = [dict(index=i, normal=v) for i, v in enumerate(surface_normals(positions, triangles))]
    return dict(entries=entries, complete=len(obj["normals"]) == obj["info"]["point_count"], surface=surface)


def connectivity_json(obj, info):
    """Spec 19.1, 19.2 (27.1, 27.2): the exact layer held, and its decode once complete with every point held. A
    layer of EXACT_MESH packets also lists `mesh` and `carried_count`, and once decoded its carried vertices."""
    c = obj["connectivity"]
    count, carried, size, crc = c["desc"]
    j = dict(triangle_count=count)
    if c["mesh"]:
        j.update(mesh=True, carried_count=carried)
    j.update(coded_size=size, coded_crc=crc, received_bytes=size if c["complete"] else len(c["have"]),
             complete=c["complete"])
    if c["L"] is not None:  # spec 19.5: once a CONNECTIVITY_REPAIR (EXACT_MESH_REPAIR) packet passed the checks
        j.update(symbol_size=c["L"], rows=[r for r, _ in c["rows"]], recovered=c["recovered"])
    if c["complete"] and len(obj["points"]) == obj["info"]["point_count"]:
        layer = exact_layer(obj, info)
        if layer is None:
            j["unusable"] = True
        else:
            j["triangles"] = layer[0]
            if c["mesh"]:
                # Each carried vertex as an entry of `points` (spec 27.3: dequantized as if it were a point).
                n = obj["info"]["point_count"]
                j["carried"] = [dict(index=n + k, q=q, **dequantize_point(q, info, obj["info"]))
                                for k, q in enumerate(layer[1])]
    return j


def objects_json(r):
    objects = []
    for i, obj in enumerate(r.objects):
        # The map fields (format 1.7) are listed only for an object whose map_level is not 0 (README).
        info = obj["info"] and {k: v for k, v in obj["info"].items() if k not in ("exact_layer", "surface_normals") and
                                (k not in ("map_level", "map_batch") or obj["info"]["map_level"])}
        o = dict(id=i, info=info, ellipsoids_received=len(obj["ellipsoids"]),
                 points_received=len(obj["points"]))
        if obj["info"] is not None:
            words = lambda store: [w for k in sorted(store) for w in [k] + store[k]]
            o["ellipsoid_digest"] = fnv(words(obj["ellipsoids"]))
            o["point_digest"] = fnv(words(obj["points"]))
            o["ellipsoids_listed"] = len(obj["ellipsoids"]) <= 300
            o["points_listed"] = len(obj["points"]) <= 300
            o["ellipsoids"] = [dict(index=k, q=q, **dequantize_ellipsoid(q, obj["info"]))
                               for k, q in sorted(obj["ellipsoids"].items())] if o["ellipsoids_listed"] else []
            o["points"] = [dict(index=k, q=q, **dequantize_point(q, r.info, obj["info"]))
                           for k, q in sorted(obj["points"].items())] if o["points_listed"] else []
            o["points_recovered"] = obj["recovered"]
            o["repair_blocks"] = [dict(first_index=b["first"], batch=b["batch"], source_count=b["k"],
                                       point_count=b["count"], rows=[row for row, _ in b["rows"]],
                                       complete=r.complete(obj, b), recovered=b["recovered"],
                                       points_recovered=b["points_recovered"])
                                  for _, b in sorted(obj["blocks"].items())]
            # Format 1.3 (spec 19): listed for an object whose entry announces an exact layer or that
            # holds a connectivity (README).
            if obj["info"]["exact_layer"] or "connectivity" in obj:
                o["exact_layer"] = obj["info"]["exact_layer"]
            if "connectivity" in obj:
                o["connectivity"] = connectivity_json(obj, r.info)
            # Format 1.8 (spec 24): listed for an object whose entry has the surface-normals flag (README).
            if obj["info"]["surface_normals"]:
                o["surface_normals"] = True
                o["normals"] = normals_json(obj, r.info)
            # Format 1.14 (spec 30): the further texture-coordinate sets, listed for an object that holds a
            # TEXCOORDS packet (README).
            if obj["texsets"] is not None:
                sets = []
                for k, s in enumerate(obj["texsets"]):
                    rng = None
                    records = []
                    if s["range"] is not None:
                        bits, origin, scale = s["range"]
                        rng = dict(bits=bits, origin=[f32(v) for v in origin], scale=[f32(v) for v in scale])
                        m = (1 << bits) - 1
                        records = [dict(index=i, q=list(q), texcoord=[f32(origin[c] + q[c] / m * scale[c]) for c in range(2)])
                                   for i, q in sorted(s["records"].items())]
                    sets.append(dict(set=k + 1, range=rng, complete=len(s["records"]) == obj["info"]["point_count"],
                                     records=records))
                o["texcoord_sets"] = dict(set_count=len(obj["texsets"]), sets=sets)
            # Format 1.5 (spec 21.2): the influence records held, listed when there is one (README).
            if obj["weights"]:
                o["weights"] = [dict(index=i, joints=j, weights=w) for i, (j, w) in sorted(obj["weights"].items())]
            # Format 1.6 (spec 22.1): the target count, attributes and displacement records held, listed when
            # there is one (README).
            # Format 1.7 (spec 23): for a mapped object, its fragments, the ranks they hold, whether its map is
            # complete, and the records held but not placed (README).
            if obj["info"]["map_level"]:
                ranks = sum(g["total"] for g in obj["fragments"].values())
                o["map"] = dict(fragments=[dict(first_rank=f, point_total=g["total"], cells=[list(c) for c in g["cells"]])
                                           for f, g in sorted(obj["fragments"].items())],
                                ranks=ranks, complete=ranks == obj["info"]["point_count"],
                                unplaced=[dict(index=i, q=q) for i, q in sorted(obj["records"].items())
                                          if i not in obj["points"]])
            if obj["morph"]:
                targets, attributes, scales = obj["morph_kind"]
                o["morph"] = dict(target_count=targets, attributes=attributes, scales=scales,
                                  records=[dict(index=i, q=q, values=[f32_product(v, scales[k // 3]) for k, v in enumerate(q)])
                                           for i, q in sorted(obj["morph"].items())])
        objects.append(o)
    return objects


def decode(buf):
    err, packets, damaged = read_container(buf)
    out = dict(file_size=len(buf), container_error=err, damaged=damaged)
    r = Receiver()
    old = Receiver(know_11=False)  # a format 1.0 decoder: the later types are unknown to it (spec 9)
    plist = []
    for offset, size, h in packets:
        result = r.add(h, offset)
        old.add(h, offset)
        name = KNOWN_10.get(h["type"]) or KNOWN_11.get(h["type"]) or KNOWN_12.get(h["type"]) or \
            KNOWN_13.get(h["type"]) or KNOWN_14.get(h["type"]) or KNOWN_15.get(h["type"]) or KNOWN_16.get(h["type"]) or \
            KNOWN_17.get(h["type"]) or KNOWN_18.get(h["type"]) or KNOWN_110.get(h["type"]) or KNOWN_111.get(h["type"]) or \
            KNOWN_112.get(h["type"]) or KNOWN_113.get(h["type"]) or KNOWN_114.get(h["type"]) or \
            "UNKNOWN(0x%02X)" % h["type"]
        plist.append(dict(offset=offset, size=size, version="%d.%d" % (h["major"], h["minor"]), type=name,
                          flags=h["flags"], stream_id=h["stream_id"], sequence=h["sequence"],
                          object_id=h["object_id"], payload_length=h["payload_length"], result=result))
    out.update(packets=plist, rejections=r.rejections, counters=r.counters, stream_id=r.stream_id,
               newest_minor=r.newest_minor)
    info = lambda rx: dict(rx.info, object_count=rx.object_count) if rx.info is not None else None
    out["stream_info"] = info(r)
    out["objects"] = objects_json(r)
    any_scene = any(h["type"] in SCENE_TYPES for _, _, h in packets)
    # Format 1.10 (README): the camera and light keys are there when the file holds a CAMERA or LIGHT packet
    # or a SCENE packet that says 1.10 or later.
    viewed = any(h["type"] in KNOWN_110 or (h["type"] == 0x10 and h["minor"] >= 10) for _, _, h in packets)
    # Format 1.12 (README): the extras keys are there when the file holds an EXTRAS packet.
    with_extras = any(h["type"] in KNOWN_112 for _, _, h in packets)
    # Format 1.13 (README): the required extensions' keys are there when the file holds a REQUIRED_EXTENSION packet.
    with_required = any(h["type"] in KNOWN_113 for _, _, h in packets)
    out["scene"] = r.scene_json(viewed, with_extras, with_required) if any_scene else None
    if any_scene:
        # The same objects but for their format 1.5 influence records and format 1.6 displacement records,
        # which a 1.0 decoder skips (README).
        geometry = [{k: v for k, v in o.items() if k not in ("weights", "morph", "texcoord_sets")} for o in out["objects"]]
        out["as_1_0"] = dict(counters=old.counters, newest_minor=old.newest_minor,
                             same_objects=info(old) == out["stream_info"] and objects_json(old) == geometry)
    out["signed"] = authenticate(packets) if any(h["type"] == 0x20 for _, _, h in packets) else None
    return out, r


def image_failures(r, path):
    """Every complete texture must be a file of its image_type: a PNG (1) or a JPEG (2) file."""
    out = []
    for k, t in sorted(r.textures.items()):
        if t["complete"]:
            problem = (png_problem if t["desc"]["image_type"] == 1 else jpeg_problem)(t["image"])
            if problem:
                out.append("%s: texture %d: %s" % (path, k, problem))
    return out


def compare(expected, actual, path, diffs):
    if len(diffs) > 20:
        return
    if isinstance(expected, bool) or isinstance(actual, bool) or expected is None or actual is None:
        if expected != actual:
            diffs.append("%s: expected %r, got %r" % (path, expected, actual))
    elif isinstance(expected, (int, float)) and isinstance(actual, (int, float)):
        if isinstance(expected, float) or isinstance(actual, float):
            # Surface normals (spec 24.3) are summed in any order: compared within 1e-4 (spec 14).
            tolerance = 1e-4 if ".normals.surface[" in path else 1e-6 * max(1.0, abs(expected), abs(actual))
            if not abs(expected - actual) <= tolerance:
                diffs.append("%s: expected %r, got %r" % (path, expected, actual))
        elif expected != actual:
            diffs.append("%s: expected %r, got %r" % (path, expected, actual))
    elif isinstance(expected, dict) and isinstance(actual, dict):
        keys = (set(expected) | set(actual)) - {"detail", "description", "vector"}
        for k in sorted(keys):
            if k not in actual or k not in expected:
                diffs.append("%s.%s: only in %s" % (path, k, "expected" if k in expected else "actual"))
            else:
                compare(expected[k], actual[k], path + "." + k, diffs)
    elif isinstance(expected, list) and isinstance(actual, list):
        if len(expected) != len(actual):
            diffs.append("%s: expected %d entries, got %d" % (path, len(expected), len(actual)))
        else:
            for i, (a, b) in enumerate(zip(expected, actual)):
                compare(a, b, "%s[%d]" % (path, i), diffs)
    elif expected != actual:
        diffs.append("%s: expected %r, got %r" % (path, expected, actual))


def main(argv):
    if len(argv) == 3 and argv[1] == "--dump":
        print(json.dumps(decode(open(os.path.join(HERE, argv[2] + ".ellc"), "rb").read())[0], indent=1))
        return 0
    failures = 0
    count = 0
    for subset in ("valid", "unusual", "faulty"):
        for name in sorted(os.listdir(os.path.join(HERE, subset))):
            if not name.endswith(".ellc"):
                continue
            base = os.path.join(HERE, subset, name[:-5])
            expected = json.load(open(base + ".json"))
            actual, receiver = decode(open(base + ".ellc", "rb").read())
            diffs = image_failures(receiver, subset + "/" + name[:-5])
            compare(expected, actual, subset + "/" + name[:-5], diffs)
            count += 1
            if diffs:
                failures += 1
                print("FAIL " + subset + "/" + name)
                for d in diffs:
                    print("  " + d)
    print("%d vectors, %d failed" % (count, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
