// The encoder: every sample becomes a valid stream, the output is deterministic, ellipsoids stay
// inside a convex shape, Draco and plain input give the same points, the command line behaves.
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"
#include "encode_options.h"
#include "shapes.h"
#include "support.h"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

using namespace ellicast;
using ellicast::test::have_sample;
using ellicast::test::fast_options;
using ellicast::test::unbudgeted;
using ellicast::test::shared_samples;

namespace {

// A closed convex polyhedron: a UV sphere squashed to radii (1, 0.6, 0.35), outward faces.
Mesh convex_shape(int n) {
    Mesh m = samples::uv_ellipsoid(n, {0, 0, 0}, {1, 0.6, 0.35});
    m.name = "convex";
    return m;
}

// Every packet of the stream, as a container, read back through the receiver.
ReceivedStream receive_all(const EncodeResult& r, std::vector<uint8_t>* file = nullptr) {
    StreamPackets packets;
    REQUIRE(packetize_stream(r.info, r.contents, 7, packets) == Error::Ok);
    std::vector<std::vector<uint8_t>> all;
    for (auto* group : {&packets.stream_info, &packets.ellipsoids, &packets.maps, &packets.points, &packets.normals})
        for (auto& p : *group) {
            CHECK(p.size() <= r.info.packet_size);
            all.push_back(p);
        }
    std::vector<uint8_t> bytes = write_container(all);
    ContainerContents contents = read_container(bytes);
    REQUIRE(contents.header_error == Error::Ok);
    CHECK(contents.damaged.empty());
    ReceivedStream rx;
    for (const auto& p : contents.packets) CHECK(rx.add_parsed(p.view, p.offset) == Error::Ok);
    if (file) *file = bytes;
    return rx;
}

std::string sample(const std::string& rel) { return (shared_samples() / rel).string(); }

}  // namespace

TEST_CASE("every sample model encodes into a stream the receiver accepts whole") {
    if (!have_sample("meshes") || !have_sample("gltf")) return;
    // Every model file under the samples, in a fixed order.
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(shared_samples())) {
        std::string ext = entry.path().extension().string();
        if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl" || ext == ".gltf" || ext == ".glb")
            files.push_back(std::filesystem::relative(entry.path(), shared_samples()).string());
    }
    std::sort(files.begin(), files.end());
    CHECK(files.size() >= 14);
    for (const std::string& f : files) {
        std::string name = f;
        CAPTURE(name);
        LoadResult loaded = load_meshes(sample(f));
        EncodeResult r = encode_meshes(loaded.meshes, fast_options());
        REQUIRE(r.info.objects.size() == loaded.meshes.size());
        ReceivedStream rx = receive_all(r);
        REQUIRE(rx.objects().size() == loaded.meshes.size());
        for (size_t i = 0; i < loaded.meshes.size(); ++i) {
            const Mesh& m = loaded.meshes[i];
            const ObjectInfo& o = r.info.objects[i];
            CHECK(rx.objects()[i].points.size() == o.point_count);
            CHECK(rx.objects()[i].ellipsoids.size() == o.ellipsoid_count);
            CHECK(o.point_count >= 1);
            CHECK(o.point_count <= m.positions.size() + r.reports[i].samples);
            CHECK(o.ellipsoid_count <= 40);
            CHECK((o.kind == ObjectKind::PointSet) == m.is_point_set);
            CAPTURE(i);
            if (!m.is_point_set) CHECK(o.ellipsoid_count >= 1);  // every surface gets a base
            if (r.reports[i].closed && r.reports[i].interior_fraction > 0) {
                CHECK(r.reports[i].flat_ellipsoids == 0);  // a closed model's ellipsoids stay inside
                CHECK(r.reports[i].outside < 0.01);
            }
            CHECK(o.has_normals() == m.has_normals());
            CHECK(o.has(kAttrTexcoord) == m.has_texcoords());
            CHECK(o.has(kAttrColor) == m.has_colors());
        }
    }
}

TEST_CASE("every distinct vertex position arrives, welded, within half a quantization step") {
    if (!have_sample("meshes/spot.obj")) return;
    LoadResult loaded = load_meshes(sample("meshes/spot.obj"));
    const Mesh& m = loaded.meshes[0];
    EncodeResult r = encode_meshes(loaded.meshes, fast_options());
    ReceivedStream rx = receive_all(r);
    auto pts = rx.points(0);
    const Frame& f = r.info.objects[0].frame;
    const double step = f.scale / ((1 << r.info.position_bits) - 1);
    std::set<std::array<uint32_t, 3>> sent;
    for (const auto& [index, q] : rx.objects()[0].points) sent.insert(q.position);
    // Seams: spot has more vertices than positions, and more points than positions (UV sets).
    CHECK(sent.size() <= pts.size());
    CHECK(sent.size() >= 2900);
    for (size_t i = 0; i < m.positions.size(); i += 7) {
        std::array<uint32_t, 3> q;
        for (int k = 0; k < 3; ++k) q[k] = uint32_t(std::lround((m.positions[i][k] - f.origin[k]) / step));
        CHECK(sent.count(q) == 1);
    }
}

TEST_CASE("the same input, options and seed give a byte-identical stream, whatever the thread count") {
    if (!have_sample("meshes/teapot.obj")) return;
    LoadResult loaded = load_meshes(sample("meshes/teapot.obj"));
    EncodeOptions a = fast_options();
    a.threads = 1;
    EncodeOptions b = fast_options();
    b.threads = 2;
    std::vector<uint8_t> fa, fb, fc;
    receive_all(encode_meshes(loaded.meshes, a), &fa);
    receive_all(encode_meshes(loaded.meshes, b), &fb);
    CHECK(fa == fb);
    EncodeOptions c = fast_options();
    c.seed = 99;
    receive_all(encode_meshes(loaded.meshes, c), &fc);
    CHECK(fa != fc);  // the seed matters
}

// A closed convex polyhedron with sharp corners: a box with a tetrahedral cap on one side.
Mesh sharp_convex_shape() {
    Mesh m;
    m.name = "sharp";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0.7f, 0}, {0, 0.7f, 0}, {0, 0, 0.4f}, {1, 0, 0.4f}, {1, 0.7f, 0.4f},
                   {0, 0.7f, 0.4f}, {1.6f, 0.35f, 0.2f}};
    m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
                   {0, 4, 7}, {0, 7, 3}, {1, 2, 8}, {2, 6, 8}, {6, 5, 8}, {5, 1, 8}};
    return m;
}

TEST_CASE("a closed sharp-edged shape gives a byte-identical stream whatever the thread count") {
    // Closed surfaces take the other paths: exact ray-crossing inside test, flat candidates, the finer measure.
    EncodeOptions a;
    a.threads = 1;
    EncodeOptions b;
    b.threads = 3;
    std::vector<uint8_t> fa, fb;
    receive_all(encode_meshes({sharp_convex_shape()}, a), &fa);
    receive_all(encode_meshes({sharp_convex_shape()}, b), &fb);
    CHECK(fa == fb);
}

TEST_CASE("ellipsoids never poke out of a convex shape by more than one quantization step") {
    for (const Mesh& shape : {convex_shape(24), sharp_convex_shape()}) {
        CAPTURE(shape.name);
        EncodeOptions o = fast_options();
        o.max_ellipsoids = 60;
        o.coverage = 1.0;  // keep adding ellipsoids: the small ones near the surface are the risky ones
        EncodeResult r = encode_meshes({shape}, o);
        const ObjectInfo& obj = r.info.objects[0];
        REQUIRE(obj.ellipsoid_count >= 5);
        const double step = obj.frame.scale / 8191.0;
        // Face planes of the convex polyhedron.
        std::vector<std::pair<Eigen::Vector3d, double>> planes;
        for (const auto& t : shape.triangles) {
            Eigen::Vector3d a(shape.positions[t[0]][0], shape.positions[t[0]][1], shape.positions[t[0]][2]);
            Eigen::Vector3d b(shape.positions[t[1]][0], shape.positions[t[1]][1], shape.positions[t[1]][2]);
            Eigen::Vector3d c(shape.positions[t[2]][0], shape.positions[t[2]][1], shape.positions[t[2]][2]);
            Eigen::Vector3d n = (b - a).cross(c - a).normalized();
            planes.push_back({n, n.dot(a)});
        }
        double worst = -1e9;
        for (const auto& q : r.contents[0].ellipsoids) {
            Ellipsoid e = dequantize_ellipsoid(q, obj.frame);
            Eigen::Matrix3d R = Eigen::Quaterniond(e.rotation[0], e.rotation[1], e.rotation[2], e.rotation[3])
                                    .normalized()
                                    .toRotationMatrix();
            Eigen::Vector3d c(e.center[0], e.center[1], e.center[2]);
            Eigen::Vector3d radii(e.radii[0], e.radii[1], e.radii[2]);
            // Support function of the ellipsoid along each plane normal: its farthest point.
            for (const auto& [n, d] : planes) {
                Eigen::Vector3d local = R.transpose() * n;
                double support = n.dot(c) + std::sqrt((radii.cwiseProduct(local)).squaredNorm());
                worst = std::max(worst, support - d);
            }
        }
        CHECK(worst <= step);
        CHECK(r.reports[0].closed);
        CHECK(r.reports[0].flat_ellipsoids == 0);
        CHECK(r.reports[0].outside < 0.01);
    }
}

TEST_CASE("Draco-compressed Box gives the same points as the plain Box within quantization") {
    if (!have_sample("gltf/Box-glb/Box.glb") || !have_sample("gltf/Box-glb/Box_Draco.glb")) return;
    EncodeResult plain = encode_meshes(load_meshes(sample("gltf/Box-glb/Box.glb")).meshes, fast_options());
    EncodeResult draco = encode_meshes(load_meshes(sample("gltf/Box-glb/Box_Draco.glb")).meshes, fast_options());
    ReceivedStream a = receive_all(plain), b = receive_all(draco);
    auto pa = a.points(0), pb = b.points(0);
    REQUIRE(pa.size() == pb.size());
    auto by_position = [](const SurfacePoint& x, const SurfacePoint& y) {
        return std::tie(x.position, x.normal) < std::tie(y.position, y.normal);
    };
    std::sort(pa.begin(), pa.end(), by_position);
    std::sort(pb.begin(), pb.end(), by_position);
    const double step = plain.info.objects[0].frame.scale / ((1 << plain.info.position_bits) - 1);
    for (size_t i = 0; i < pa.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            CHECK(std::abs(pa[i].position[k] - pb[i].position[k]) <= 2 * step);
            CHECK(std::abs(pa[i].normal[k] - pb[i].normal[k]) <= 0.01);
        }
}

TEST_CASE("a closed model's interior is mostly covered and little volume lies outside") {
    if (!have_sample("meshes/spot.obj")) return;
    EncodeOptions o = fast_options();
    o.grid = 48;
    o.max_ellipsoids = 150;
    o.candidates = 600;
    EncodeResult r = encode_meshes(load_meshes(sample("meshes/spot.obj")).meshes, o);
    CHECK(r.reports[0].closed);
    CHECK(r.reports[0].coverage > 0.85);
    CHECK(r.reports[0].outside < 0.01);
}

TEST_CASE("sharp-edged closed models (a box, the fandisk) are covered to the 95% target with the ellipsoids they need") {
    // The Box's bytes warrant 13 ellipsoids by default (base_ratio: 85.7% covered, no warning, see
    // below); with the whole budget it reaches the target.
    for (const char* rel : {"gltf/Box-glb/Box.glb", "meshes/fandisk.obj"}) {
        if (!have_sample(rel)) continue;
        CAPTURE(rel);
        EncodeResult r = encode_meshes(load_meshes(sample(rel)).meshes, unbudgeted());
        REQUIRE(r.reports.size() == 1);
        CHECK(r.reports[0].closed);
        CHECK(r.reports[0].coverage >= 0.95);
        CHECK(r.reports[0].outside <= 0.01);
        CHECK(r.reports[0].ellipsoids <= 400);
        CHECK(r.warnings.empty());
    }
}

TEST_CASE("each object of a scene of many small closed objects is still covered to the target") {
    // Past 8 objects each gets fewer seeds and a coarser grid; the coverage target still holds.
    std::vector<Mesh> scene;
    for (int i = 0; i < 12; ++i) {
        Mesh m = convex_shape(8);
        for (auto& p : m.positions) p[0] += 2.5f * float(i);
        scene.push_back(m);
    }
    EncodeOptions o;
    o.max_ellipsoids = 100;
    EncodeResult r = encode_meshes(scene, o);
    REQUIRE(r.reports.size() == scene.size());
    for (const auto& rep : r.reports) {
        CHECK(rep.closed);
        CHECK(rep.coverage >= 0.95);
        CHECK(rep.outside <= 0.01);
        CHECK(rep.ellipsoids <= 100);
    }
}

TEST_CASE("a flat sheet with no inside still gets flat ellipsoids hugging it") {
    Mesh sheet;
    sheet.name = "sheet";
    const int n = 20;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) sheet.positions.push_back({float(i) / n, float(j) / n, 0.05f * float(i * j) / (n * n)});
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            uint32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
            sheet.triangles.push_back({a, c, d});
            sheet.triangles.push_back({a, d, b});
        }
    EncodeResult r = encode_meshes({sheet}, fast_options());
    const auto& rep = r.reports[0];
    CHECK(rep.flat_ellipsoids >= 1);
    CHECK(rep.surface_covered >= 0.0);
    // Every ellipsoid is flat: its smallest radius is much smaller than its largest.
    for (const auto& q : r.contents[0].ellipsoids) {
        Ellipsoid e = dequantize_ellipsoid(q, r.info.objects[0].frame);
        auto [lo, hi] = std::minmax({e.radii[0], e.radii[1], e.radii[2]});
        CHECK(lo * 3 < hi);
    }
}

TEST_CASE("encoder options out of range are refused with a message naming the option") {
    Mesh m = convex_shape(6);
    auto refused = [&](EncodeOptions o, const std::string& word) {
        std::string why = check_encode_options(o);
        CHECK(why.find(word) != std::string::npos);
        CHECK_THROWS_AS(encode_meshes({m}, o), std::invalid_argument);
    };
    EncodeOptions o;
    o.max_ellipsoids = 0;
    refused(o, "ellipsoid count");
    o = {};
    o.coverage = 1.5;
    refused(o, "coverage");
    o = {};
    o.position_bits = 20;
    refused(o, "position bits");
    o = {};
    o.packet_size = 64;
    refused(o, "packet size");
    o = {};
    o.grid = 5000;
    refused(o, "grid");
    CHECK_THROWS_AS(encode_meshes({}, EncodeOptions{}), std::invalid_argument);
}

TEST_CASE("the encoder refuses a mesh with a non-finite coordinate, a bad index or a short attribute array") {
    Mesh good = convex_shape(6);
    Mesh nan = good;
    nan.positions[3][1] = NAN;
    Mesh index = good;
    index.triangles[2][1] = 100000;
    Mesh normals = good;
    normals.normals.resize(3);
    for (const Mesh* m : {&nan, &index, &normals}) CHECK_THROWS_AS(encode_meshes({*m}, fast_options()), std::invalid_argument);
    try {
        encode_meshes({nan}, fast_options());
    } catch (const std::invalid_argument& e) {
        CHECK(std::string(e.what()).find("vertex 3") != std::string::npos);
    }
}

TEST_CASE("ellicast encode writes a stream, refuses to overwrite its input and rejects absurd options") {
    if (!have_sample("meshes/woody.obj")) return;
    auto dir = ellicast::test::scratch_dir("encode_cli");
    const std::string exe = ellicast::test::ellicast_exe().string();
    const std::string input = sample("meshes/woody.obj");
    const std::string out = (dir / "woody.ellc").string();
    auto run = [&](const std::string& args) {
        int status = std::system((exe + " " + args + " > " + (dir / "out.txt").string() + " 2> " +
                                  (dir / "err.txt").string()).c_str());
        return WEXITSTATUS(status);
    };
    auto text = [&](const char* name) {
        std::ifstream in(dir / name);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    CHECK(run("encode -q --grid 32 -e 30 " + input + " -o " + out) == 0);
    CHECK(std::filesystem::file_size(out) > 0);
    CHECK(text("out.txt").find("bytes per point") != std::string::npos);
    std::vector<uint8_t> bytes;
    std::string message;
    REQUIRE(read_file(out, bytes, message) == Error::Ok);
    CHECK(read_container(bytes).damaged.empty());

    // The input is never overwritten.
    std::filesystem::copy_file(input, dir / "copy.obj");
    auto before = std::filesystem::file_size(dir / "copy.obj");
    CHECK(run("encode -q " + (dir / "copy.obj").string() + " -o " + (dir / "copy.obj").string()) == 2);
    CHECK(std::filesystem::file_size(dir / "copy.obj") == before);
    CHECK(text("err.txt").find("refusing to overwrite") != std::string::npos);

    CHECK(run("encode -q " + input + " -o " + out + " --coverage 7") == 2);
    CHECK(text("err.txt").find("coverage") != std::string::npos);
    CHECK(run("encode -q " + input + " -o " + out + " --packet-size 10") == 2);
    CHECK(text("err.txt").find("packet size") != std::string::npos);
    CHECK(run("encode -q " + (dir / "missing.obj").string() + " -o " + out) == 3);
    CHECK(text("err.txt").find("missing.obj") != std::string::npos);
}

TEST_CASE("any fifth of the point packets is spread over the whole surface") {
    if (!have_sample("meshes/bunny.ply")) return;
    LoadResult loaded = load_meshes(sample("meshes/bunny.ply"));
    const Mesh& m = loaded.meshes[0];
    EncodeOptions o = fast_options();
    o.max_ellipsoids = 4;
    o.candidates = 16;
    o.grid = 16;
    EncodeResult r = encode_meshes(loaded.meshes, o);
    StreamPackets packets;
    REQUIRE(packetize_stream(r.info, r.contents, 1, packets) == Error::Ok);
    REQUIRE(packets.points.size() >= 50);
    // Keep every fifth POINTS packet (a loss of 80%), starting at several offsets.
    const Frame& f = r.info.objects[0].frame;
    for (size_t offset = 0; offset < 5; offset += 2) {
        ReceivedStream rx;
        for (auto& p : packets.stream_info) rx.add_packet(p, 0);
        for (auto& p : packets.maps) rx.add_packet(p, 0);  // the base's map (format 1.7)
        for (size_t i = offset; i < packets.points.size(); i += 5) rx.add_packet(packets.points[i], i);
        auto pts = rx.points(0);
        REQUIRE(pts.size() > m.positions.size() / 6);
        // Bucket the received points on a grid of cells 1/16 of the model's size: nearly every
        // vertex of the model lies in a cell that received points (only cells holding a handful of
        // vertices may miss out, as with any order).
        const int n = 16;
        auto cell = [&](const std::array<float, 3>& p) {
            std::array<int, 3> c;
            for (int k = 0; k < 3; ++k) c[k] = std::clamp(int((p[k] - f.origin[k]) / f.scale * n), 0, n - 1);
            return c;
        };
        std::set<std::array<int, 3>> have;
        for (const auto& p : pts) have.insert(cell(p.position));
        size_t missing = 0;
        for (const auto& p : m.positions) missing += !have.count(cell(p));
        CAPTURE(offset);
        CHECK(missing * 100 <= m.positions.size());  // at most 1% of the vertices in an empty cell
    }
}

TEST_CASE("a box's base follows its bytes: a dozen ellipsoids, no coverage warning, the budget in the report") {
    if (!have_sample("gltf/Box-glb/Box.glb")) return;
    const EncodeResult r = encode_meshes(load_meshes(sample("gltf/Box-glb/Box.glb")).meshes, EncodeOptions{});
    REQUIRE(r.reports.size() == 1);
    MESSAGE("the Box: " << r.reports[0].ellipsoids << " ellipsoids of a budget of " << r.reports[0].ellipsoid_budget
                        << ", coverage " << r.reports[0].coverage);
    CHECK(r.reports[0].ellipsoid_budget >= 8);
    CHECK(r.reports[0].ellipsoid_budget <= 20);  // 24 points of 9 bytes and 12 triangles: about 230 bytes
    CHECK(r.reports[0].ellipsoids <= r.reports[0].ellipsoid_budget);
    CHECK(r.reports[0].coverage > 0.75);
    CHECK(r.warnings.empty());  // short of the target on purpose
    EncodeOptions o;
    o.base_ratio = -1;
    CHECK_THROWS_AS(encode_meshes(load_meshes(sample("gltf/Box-glb/Box.glb")).meshes, o), std::invalid_argument);
}

TEST_CASE("a box whose faces have their own corners is closed, also where a corner's copies say 0 and -0") {
    // Welded by position as floats compare: 0 and -0 are one position. Each face's corners on the
    // planes x = 0, y = 0, z = 0 are written as 0 by some faces and -0 by others.
    Mesh m = samples::box({1, 1, 1});
    for (auto& p : m.positions)
        for (auto& c : p) c += 0.5f;  // corners at 0 and 1
    size_t negative = 0;
    for (size_t i = 0; i < m.positions.size(); ++i)
        for (auto& c : m.positions[i])
            if (c == 0.0f && i % 2 == 1) c = -0.0f, ++negative;
    REQUIRE(negative > 0);
    EncodeOptions o = fast_options();
    const EncodeResult r = encode_meshes({m}, o);
    REQUIRE(r.reports.size() == 1);
    CHECK(r.reports[0].closed);
    CHECK(r.warnings.empty());
}

TEST_CASE("an object's points, made beside its ellipsoids on a guess, are those made after them, the guess right or wrong") {
    // With worker threads the points start before the ellipsoids are known, guessing flat ellipsoids
    // (denser samples) on an open surface and none on a closed one; a wrong guess is made again.
    Mesh sheet;  // open, no inside: flat ellipsoids
    sheet.name = "sheet";
    for (int y = 0; y <= 8; ++y)
        for (int x = 0; x <= 8; ++x) sheet.positions.push_back({0.1f * float(x), 0.1f * float(y), 0.02f * float(x % 2)});
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const uint32_t a = y * 9 + x;
            sheet.triangles.push_back({a, a + 1, a + 10});
            sheet.triangles.push_back({a, a + 10, a + 9});
        }
    Mesh holed = samples::uv_ellipsoid(16, {0, 0, 0}, {1.0, 0.8, 0.6});  // open, bulky: none flat
    holed.name = "holed";
    holed.triangles.resize(holed.triangles.size() - 6);
    Mesh closed = samples::uv_ellipsoid(16, {0, 0, 0}, {1.0, 0.8, 0.6});  // closed: none flat
    closed.name = "closed";
    bool open_flat = false, open_none = false;
    for (const Mesh& m : {sheet, holed, closed}) {
        CAPTURE(m.name);
        EncodeOptions one = fast_options(), two = fast_options();
        one.threads = 1;
        two.threads = 2;
        const EncodeResult a = encode_meshes({m}, one), b = encode_meshes({m}, two);
        std::vector<uint8_t> fa, fb;
        receive_all(a, &fa);
        receive_all(b, &fb);
        CHECK(fa == fb);
        REQUIRE(a.reports.size() == 1);
        CHECK(a.reports[0].samples == b.reports[0].samples);
        CHECK(a.reports[0].flat_ellipsoids == b.reports[0].flat_ellipsoids);
        CHECK(a.warnings == b.warnings);
        if (!a.reports[0].closed) (a.reports[0].flat_ellipsoids > 0 ? open_flat : open_none) = true;
    }
    CHECK(open_flat);  // the guess right
    CHECK(open_none);  // and wrong
}
