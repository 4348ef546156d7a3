// Inside-out and inconsistently wound input: the encoder turns parts that face inward (or whose
// triangles disagree with their neighbours) before its inside test, warns, and gets the same
// ellipsoids as from the correctly wound model.
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/mesh_input.h"
#include "encode_options.h"
#include "shapes.h"
#include "support.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <utility>

using namespace ellicast;
using namespace ellicast::test;

namespace {

Mesh turned_round(Mesh m) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    return m;
}

// Appends b's vertices and triangles to a.
void append(Mesh& a, const Mesh& b) {
    const uint32_t base = uint32_t(a.positions.size());
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    for (auto t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

std::string sample(const std::string& rel) { return (shared_samples() / rel).string(); }

// The ellipsoids of one object as their 16-byte records, for comparing bit for bit.
std::vector<std::array<uint8_t, kEllipsoidBytes>> records(const ObjectContent& c) {
    std::vector<std::array<uint8_t, kEllipsoidBytes>> out(c.ellipsoids.size());
    for (size_t i = 0; i < out.size(); ++i) pack_ellipsoid(c.ellipsoids[i], out[i].data());
    return out;
}

bool same_points(const ObjectContent& a, const ObjectContent& b) {
    if (a.points.size() != b.points.size()) return false;
    for (size_t i = 0; i < a.points.size(); ++i) {
        const QuantizedPoint &p = a.points[i], &q = b.points[i];
        if (p.position != q.position || p.normal != q.normal || p.texcoord != q.texcoord || p.color != q.color) return false;
    }
    return true;
}

bool warned_about(const EncodeResult& r, const std::string& what) {
    return std::any_of(r.warnings.begin(), r.warnings.end(),
                       [&](const std::string& w) { return w.find(what) != std::string::npos; });
}

}  // namespace

TEST_CASE("a closed sample whose faces all point inward gets the ellipsoids of the original, with a warning") {
    for (const char* f : {"meshes/spot.obj", "meshes/fandisk.obj", "gltf/Duck/Duck.gltf"}) {
        if (!have_sample(f)) continue;
        CAPTURE(f);
        const std::vector<Mesh> original = load_meshes(sample(f)).meshes;
        std::vector<Mesh> reversed;
        for (const Mesh& m : original) reversed.push_back(turned_round(m));
        // Every normal in the records (format 1.7's way): turned round, the Duck's triangles no longer
        // agree with its normals, so surface normals (format 1.8) would leave different points to the
        // surface, and the records, the map and the point order would differ with them.
        EncodeOptions options = fast_options();
        options.normal_tolerance = 0;
        const EncodeResult a = encode_meshes(original, options);
        const EncodeResult b = encode_meshes(reversed, options);
        CHECK_FALSE(warned_about(a, "inward"));
        CHECK(warned_about(b, "inward"));
        REQUIRE(a.contents.size() == b.contents.size());
        for (size_t i = 0; i < a.contents.size(); ++i) {
            CHECK(a.reports[i].turned_faces == 0);
            CHECK(b.reports[i].turned_faces == original[i].triangles.size());
            CHECK(b.reports[i].ellipsoids > 0);
            CHECK(b.reports[i].coverage == doctest::Approx(a.reports[i].coverage));
            CHECK(records(a.contents[i]) == records(b.contents[i]));
            CHECK(same_points(a.contents[i], b.contents[i]));
        }
    }
}

TEST_CASE("a ball reversed by another corner order still fills its inside") {
    Mesh ball = samples::uv_ellipsoid(24, {0, 0, 0}, {1, 0.8, 0.6});
    Mesh reversed = ball;
    for (auto& t : reversed.triangles) t = {t[2], t[1], t[0]};
    const EncodeResult a = encode_meshes({ball}, fast_options());
    const EncodeResult b = encode_meshes({reversed}, fast_options());
    CHECK(b.reports[0].turned_faces == ball.triangles.size());
    CHECK(b.reports[0].coverage > 0.9);
    CHECK(b.reports[0].coverage == doctest::Approx(a.reports[0].coverage).epsilon(0.02));
}

TEST_CASE("triangles wound against their neighbours are mended, and the model encodes as the consistent one") {
    const Mesh ball = samples::uv_ellipsoid(20, {0, 0, 0}, {1, 1, 1});
    Mesh patchy = ball;
    size_t turned = 0;
    for (size_t i = 0; i < patchy.triangles.size(); i += 7, ++turned) std::swap(patchy.triangles[i][1], patchy.triangles[i][2]);
    const EncodeResult a = encode_meshes({ball}, fast_options());
    const EncodeResult b = encode_meshes({patchy}, fast_options());
    CHECK(b.reports[0].turned_faces == turned);
    CHECK(warned_about(b, "facing against their neighbours"));
    CHECK(records(a.contents[0]) == records(b.contents[0]));
}

TEST_CASE("one inward part among outward ones is turned, and only that part") {
    Mesh two = samples::uv_ellipsoid(16, {-2, 0, 0}, {1, 1, 1});
    const Mesh other = turned_round(samples::uv_ellipsoid(16, {2, 0, 0}, {1, 1, 1}));
    append(two, other);
    const EncodeResult r = encode_meshes({two}, fast_options());
    CHECK(r.reports[0].turned_faces == other.triangles.size());
    CHECK(warned_about(r, "1 of 2 parts face inward"));
    CHECK(r.reports[0].coverage > 0.9);
}

TEST_CASE("a hollow ball's inner wall faces its cavity and is left alone, facing out, it is turned") {
    const Mesh outer = samples::uv_ellipsoid(20, {0, 0, 0}, {1, 1, 1});
    const Mesh inner_right = turned_round(samples::uv_ellipsoid(12, {0, 0, 0}, {0.5, 0.5, 0.5}));
    Mesh hollow = outer;
    append(hollow, inner_right);
    const EncodeResult right = encode_meshes({hollow}, fast_options());
    CHECK(right.reports[0].turned_faces == 0);
    CHECK(right.warnings.empty());

    Mesh wrong = outer;
    append(wrong, samples::uv_ellipsoid(12, {0, 0, 0}, {0.5, 0.5, 0.5}));
    const EncodeResult mended = encode_meshes({wrong}, fast_options());
    CHECK(mended.reports[0].turned_faces == inner_right.triangles.size());
    CHECK(records(right.contents[0]) == records(mended.contents[0]));
}

TEST_CASE("a flat part has no inside: a label's two quads (a card's faces, rounding noise off their plane) keep their winding, without a warning") {
    // The labels of Khronos ClearCoatTest: a front quad at z = 0 facing +z and a back one at z = -0.01
    // facing -z, each off its plane by about 4e-8 (as exported); judged by the sign of their noise
    // volume they were "turned to face outward" with a warning.
    Mesh label;
    const float noise = 3.75e-8f;
    label.positions = {{-2, -0.23f, -noise}, {2, -0.23f, -noise}, {2, 0.23f, noise}, {-2, 0.23f, noise},
                       {2, -0.23f, -0.01f}, {-2, -0.23f, -0.0100001f}, {-2, 0.23f, -0.01000008f}, {2, 0.23f, -0.0100004f}};
    label.triangles = {{0, 1, 2}, {3, 0, 2}, {4, 5, 6}, {7, 4, 6}};
    const EncodeResult r = encode_meshes({label}, fast_options());
    CHECK(r.reports[0].turned_faces == 0);
    CHECK_FALSE(warned_about(r, "face inward"));
    CHECK_FALSE(warned_about(r, "faces inward"));
    // Turned round, it is left turned round: a flat part has no side to prefer.
    const EncodeResult t = encode_meshes({turned_round(label)}, fast_options());
    CHECK(t.reports[0].turned_faces == 0);
}
