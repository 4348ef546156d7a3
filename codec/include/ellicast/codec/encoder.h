// The ellicast encoder: meshes in, a quantized stream out (stream info and, per object, ellipsoids,
// points and, where it sends them, the exact layer's coded triangles and the normal entries of
// surface normals), ready for packetize_stream() and packetize_connectivity(). It is the reference
// encoder of spec/format.md: section 12 (Sender behaviour), 19.6, 23.7 and 24.5 (the sender
// behaviour of the exact layer, mapped points and surface normals).
//
// For each triangle mesh (after Bischoff & Kobbelt 2002):
//  1. inside/outside from generalized winding numbers on a voxel grid (robust on open meshes);
//  2. candidate ellipsoids: seeds on the surface, a sphere grown inward until it touches the
//     surface (shrinking ball), then stretched into an ellipsoid while it stays inside;
//  3. greedy selection: largest first, then largest gain of covered interior volume, until the
//     coverage target or the count; then the candidates that best cover surface still far from
//     the base (thin parts); flat ellipsoids hugging the surface where there is no inside (sheets);
//  4. every selected ellipsoid is quantized and checked again: dequantized, it must still be
//     clear of the surface, else it is shrunk;
//  5. the points: every original vertex, plus surface samples where triangles are large (low-poly
//     models), welded by quantized position and attributes, in an order in which any subset is
//     spread evenly over the surface;
//  6. the exact layer: the original triangles coded over the points (format 1.3); the map level at
//     which MAPPED_POINTS packets over a POINT_MAP are smallest, the points then in the map's order
//     (1.7); and the normals left to the exact layer's surface where they agree with it (1.8).
// Deterministic: the same meshes, options and seed give the same output, whatever the threads.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/format.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace ellicast {

struct EncodeOptions {
    uint32_t max_ellipsoids = 400;   // per object, 1..100000
    double coverage = 0.95;          // covered fraction of interior volume aimed at, (0, 1]
    uint32_t candidates = 0;         // seeds grown into candidate ellipsoids; 0: automatic
    uint32_t grid = 0;               // voxel grid cells along the longest axis (16..256); 0: automatic
    uint8_t position_bits = 14;      // 8..16
    uint8_t normal_bits = 10;        // 4..16
    uint8_t texcoord_bits = 12;      // 4..16
    uint8_t color_bits = 8;          // 2..16
    uint16_t packet_size = kDefaultPacketSize;
    uint32_t seed = 1;
    // Surface samples added to the original vertices where triangles are large: no edge inside a
    // face longer than this fraction of the object's bounding-box diagonal, half of it along
    // creases and boundaries (both halved again on an object with sheets, whose thin base has two
    // sides to fill). 0: the original vertices only. [0, 1]
    double sample_spacing = 0.03;
    // At most this many samples per object, or as many as it has vertices if that is more (the
    // spacings grow until they fit). Counted as the stream's points: a seam's attribute sets count
    // once each. 40000 lets the milk truck's body (1,856 vertices, thin bumpers through its shell)
    // keep the default spacing and come back within 0.1%; 20000 left it at 0.12%. 0..10000000
    uint32_t max_samples = 40000;
    // At most this many samples per original vertex of the object (the samples' bytes follow the
    // points'): samples only serve a receiver whose exact layer is not whole yet, and every one of
    // them makes each carousel cycle longer, so what a stream spends on them stays in proportion to
    // what the exact asset costs. A box of 24 vertices gets none (9,522 without the budget: a
    // 127 KB stream for a 1 KB asset); spot keeps its 798 (a quarter of its 3,225 vertices); a scan,
    // whose vertices already cover its surface, needs few. At 50% loss, on one clock
    // (bench_sample_budget), the Box is exact after 0.08 of the unbudgeted stream's cycles instead
    // of 2.5, the Duck after 1.35 instead of never within 4, with no worse a picture before.
    // Negative: no limit but max_samples. [-1, 1000]
    double sample_budget = 0.25;
    // The base follows the bytes too: an object's ellipsoids take at most this multiple of the bytes
    // its exact data is estimated at (its vertices as point records, a byte a triangle), and at least
    // 8 ellipsoids; never more than max_ellipsoids. A 4-vertex square had 295 ellipsoids (4.9 KB)
    // for 99 bytes of points and triangles, the 24-vertex Box 50 (832 bytes) for 278: the first
    // picture of an object that small costs more than the object itself. 0: max_ellipsoids alone.
    // [0, 1000]
    double base_ratio = 1.0;
    unsigned threads = 2;            // worker threads (results do not depend on it); past 1, one more makes the points beside the ellipsoids
    // Repair packets (format 1.2, spec 17): POINTS_REPAIR symbols per block of POINTS packets, as a
    // multiple of the block's source count (blocks hold at most floor(255 / (1 + ratio)) POINTS
    // packets). 1: as many repair symbols as sources, which the carousel interleaves one for one. 0:
    // none (a carousel then repeats the POINTS packets). [0, 4]
    double repair_ratio = 1.0;
    // The exact layer (format 1.3, spec 19): each object's original triangles, coded over its points,
    // sent in CONNECTIVITY packets, so that a receiver holding every point shows the original mesh.
    bool exact_layer = true;
    // Mapped points (format 1.7, spec 23): send an object's points as MAPPED_POINTS over a POINT_MAP
    // of occupied cells, at the map level that makes them smallest, where that beats POINTS. false:
    // POINTS packets, readable by 1.6 decoders.
    bool point_map = true;
    // Surface normals (format 1.8, spec 24): an object with normals and an exact layer sends only the
    // normals further than this many degrees from its surface's (the angle-weighted normal over the
    // exact layer's triangles); the others a receiver computes. 0: every normal in the point
    // records, readable with normals by 1.7 decoders. [0, 90]
    double normal_tolerance = 2.0;
    // Carried vertices (format 1.11, spec 27): of an object with an exact layer, no normals in its
    // records (surface normals: only the vertices whose normal is not sent) and no per-point data,
    // only this share of its vertices (the first in the spread order) travel as points; the exact layer carries the others, coded against its triangles (about 2.3 bytes a
    // vertex on a dense scan, against 3.3 as a mapped point). Lower: a smaller stream and an exact
    // object sooner, fewer points for the picture before it. 1: every vertex a point (a stream
    // 1.10 decoders show exact). [0, 1]
    double point_share = 1.0;
    // Called with a stage name and the fraction done (0..1); may be empty.
    std::function<void(const std::string& stage, double fraction)> progress;
};

// Checks an options record: empty when valid, else a message naming the first bad option.
std::string check_encode_options(const EncodeOptions& options);

// What the encoder did for one object.
struct ObjectReport {
    std::string name;
    bool point_set = false;
    uint32_t vertices = 0;            // input vertices
    uint32_t points = 0;              // points sent (after welding), samples included
    uint32_t samples = 0;             // surface samples added to the vertices (distinct position and attributes)
    uint32_t candidates = 0;          // candidate ellipsoids grown
    uint32_t ellipsoids = 0;          // ellipsoids sent
    uint32_t ellipsoid_budget = 0;    // the ellipsoids its bytes warrant (EncodeOptions::base_ratio), when below max_ellipsoids; else 0
    uint32_t surface_ellipsoids = 0;  // of those, chosen for surface (thin parts) rather than volume
    uint32_t flat_ellipsoids = 0;     // of those, flat ones straddling a sheet without inside
    uint32_t shrunk = 0;              // ellipsoids shrunk after quantization to stay inside
    bool closed = false;              // no boundary edges
    uint32_t exact_triangles = 0;     // triangles in the exact layer (0: none sent)
    uint32_t connectivity_bytes = 0;  // their coded size
    uint32_t carried = 0;             // format 1.11: vertices the exact layer carries (not points)
    uint8_t map_level = 0;            // format 1.7: the level of the object's point map (0: POINTS)
    uint64_t plain_point_bytes = 0;   // POINTS packets the points would take
    uint64_t map_bytes = 0;           // POINT_MAP packets (0 without a map)
    uint64_t mapped_point_bytes = 0;  // MAPPED_POINTS packets (0 without a map)
    bool surface_normals = false;     // format 1.8: normals left to the surface where they agree
    uint32_t normals_sent = 0;        // of the points, those whose normal NORMALS packets send
    uint32_t texcoord_sets = 0;       // format 1.14: further texture-coordinate sets sent (TEXCOORD_1, ...)
    uint32_t turned_faces = 0;        // triangles encoded turned round: parts that faced inward or
                                      // against their neighbours (the input is not changed)
    double interior_fraction = 0;     // of the grid's voxels, inside the surface
    double coverage = 0;              // covered fraction of the interior volume (dequantized ellipsoids)
    double outside = 0;               // volume of the ellipsoids outside the model / interior volume
                                      // (both on a grid twice as fine as `grid` for a surface
                                      // without boundary, else on `grid`)
    double surface_covered = 0;       // fraction of surface samples near the base
    uint32_t grid[3] = {0, 0, 0};     // voxel grid used
};

struct EncodeResult {
    StreamInfo info;
    std::vector<ObjectContent> contents;  // one per object, in info.objects order
    std::vector<ObjectReport> reports;
    std::vector<std::string> warnings;
};

// Encodes meshes as the objects of one stream (one object per mesh, in order). Throws
// std::invalid_argument for invalid options, no meshes, more than kMaxObjects meshes, or a mesh
// with no vertices, a non-finite coordinate, an index out of range or an attribute array of the
// wrong size (the message names the mesh and the vertex or triangle).
EncodeResult encode_meshes(const std::vector<Mesh>& meshes, const EncodeOptions& options);

}  // namespace ellicast
