// ellicast format 1.14 (this library reads format 1.0 to 1.14): packets, their payloads, quantization,
// the receiver's state, container files. This header includes every header of the format library;
// each of them can also be included alone.
//
// The normative description is spec/format.md; these headers are its reference implementation.
// Depends on nothing but the standard library: no geometry algorithms, no glTF.
//
// Every parse function takes bytes it does not trust: it checks each length against what is
// really there, allocates at most in proportion to the input, and returns an error code that
// names what was wrong instead of throwing or crashing.
//
// The headers, in dependency order (spec/format.md sections in brackets):
//   format/constants.h            versions, packet layout constants, packet types, kNone [3, 4, 9]
//   format/error.h                Error, the reason a packet or file was rejected [11.1, 11.3]
//   format/utf8.h                 UTF-8 checks for names and patches [15, 18.2]
//   format/packet.h               packet header, CRC-32C, writing, parsing, restamping packets [3, 11.1]
//   format/stream_info.h          StreamInfo, ObjectInfo, Frame: the stream-level fields, the object table [5]
//   format/quantize.h             Ellipsoid, SurfacePoint, their quantized forms, octahedral normals [6.1, 7.1, 8]
//   format/payloads.h             STREAM_INFO, ELLIPSOIDS, POINTS / MAPPED_POINTS payloads, per-packet counts [5-7, 23.4]
//   format/point_map.h            mapped points (1.7): cells, ranks, POINT_MAP payloads, the map level [23]
//   format/normals.h              surface normals (1.8): NORMALS payloads, the surface normal of a point [24]
//   format/texcoords.h            further texture-coordinate sets (1.14): TEXCOORDS payloads [30]
//   format/packetize.h            ObjectContent and packetize_stream: a whole stream's geometry in packets [12]
//   format/material_extensions.h  MATERIAL_EXTENSIONS (1.3): a material's JSON patch and its checks [18]
//   format/animation.h            ANIMATION (1.4) and MORPH_ANIMATION (1.6) payloads, SceneAnimation [20, 22.2]
//   format/skin.h                 SKIN and JOINT_WEIGHTS (1.5) payloads, influences [21]
//   format/morph.h                MORPH_DELTAS (1.6) payloads: morph target displacements [22.1]
//   format/camera_light.h        CAMERA and LIGHT (1.10) payloads: cameras and punctual lights [26]
//   format/extras.h              EXTRAS (1.12) payloads: the glTF extras of the asset and the scene's elements [28]
//   format/scene.h                SCENE, MATERIAL, TEXTURE_FRAGMENT (1.1), SceneDescription, packetize_scene [15]
//   format/manifest.h             MANIFEST (1.2) layout, packet digests, SHA-256 [16]
//   format/repair.h               POINTS_REPAIR (1.2): the erasure code over points [17]
//   format/connectivity.h         the exact layer (1.3): coded triangles, CONNECTIVITY(_REPAIR) payloads [19]
//   format/received_stream.h      ReceivedStream, the receiver's state, and what a receiver shows [11, ...]
//   format/container.h            .ellc container files, reading and writing whole files [10]
#pragma once

#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"
#include "ellicast/format/utf8.h"
#include "ellicast/format/packet.h"
#include "ellicast/format/stream_info.h"
#include "ellicast/format/quantize.h"
#include "ellicast/format/payloads.h"
#include "ellicast/format/point_map.h"
#include "ellicast/format/normals.h"
#include "ellicast/format/texcoords.h"
#include "ellicast/format/packetize.h"
#include "ellicast/format/material_extensions.h"
#include "ellicast/format/animation.h"
#include "ellicast/format/skin.h"
#include "ellicast/format/morph.h"
#include "ellicast/format/camera_light.h"
#include "ellicast/format/extras.h"
#include "ellicast/format/required_extensions.h"
#include "ellicast/format/scene.h"
#include "ellicast/format/manifest.h"
#include "ellicast/format/repair.h"
#include "ellicast/format/connectivity.h"
#include "ellicast/format/received_stream.h"
#include "ellicast/format/container.h"
