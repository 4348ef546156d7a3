// Pictures of meshes: what `ellicast render` draws.
#include "support.h"

#include "ellicast/converters/render.h"

#include <cmath>
#include <cstdlib>
#include <fstream>

using namespace ellicast;

namespace {

// An octahedron of radius 1 around the origin, coloured red.
Mesh octahedron() {
    Mesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    m.colors.assign(6, {1, 0, 0, 1});
    return m;
}

}  // namespace

TEST_CASE("a rendered mesh covers the middle of the picture and leaves the corners as background") {
    RenderOptions o;
    o.width = 64;
    o.height = 48;
    std::array<double, 3> lo, hi;
    bounding_box({octahedron()}, lo, hi);
    Image img = render_meshes({octahedron()}, lo, hi, o);
    REQUIRE(img.width == 64);
    REQUIRE(img.height == 48);
    auto px = [&](int x, int y, int k) { return img.rgb[(size_t(y) * img.width + x) * 3 + k]; };
    CHECK(px(32, 24, 0) > 100);  // red surface
    CHECK(px(32, 24, 1) < 30);
    CHECK(px(0, 0, 0) == px(0, 0, 1));  // grey background
    o.use_colors = false;
    Image grey = render_meshes({octahedron()}, lo, hi, o);
    CHECK(std::abs(int(grey.rgb[(24 * 64 + 32) * 3]) - int(grey.rgb[(24 * 64 + 32) * 3 + 1])) < 20);
}

TEST_CASE("panels side by side keep their pixels and are written as a PNG file") {
    RenderOptions o;
    o.width = o.height = 32;
    std::array<double, 3> lo{-1, -1, -1}, hi{1, 1, 1};
    Image a = render_meshes({octahedron()}, lo, hi, o);
    Image both = side_by_side({a, a});
    CHECK(both.width > 2 * a.width);
    CHECK(both.height == a.height);
    CHECK(both.rgb[(16 * both.width + 16) * 3] == a.rgb[(16 * a.width + 16) * 3]);
    auto dir = test::scratch_dir("render");
    write_png((dir / "two.png").string(), both);
    std::ifstream f(dir / "two.png", std::ios::binary);
    char sig[8] = {};
    f.read(sig, 8);
    CHECK(std::string(sig + 1, 3) == "PNG");
    CHECK_FALSE(std::filesystem::exists(dir / "two.png.partial"));
}

TEST_CASE("a label is written in dark pixels on a light band across the top of a panel, and nowhere else") {
    RenderOptions o;
    o.width = o.height = 96;
    std::array<double, 3> lo{-1, -1, -1}, hi{1, 1, 1};
    const Image plain = render_meshes({octahedron()}, lo, hi, o);
    Image labelled = plain;
    draw_label(labelled, "60% lost", 2);
    auto dark = [](const Image& img, int y0, int y1) {
        size_t n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < img.width; ++x) n += img.rgb[(size_t(y) * img.width + x) * 3] < 60;
        return n;
    };
    CHECK(dark(labelled, 0, 32) > 40);  // the glyphs: the band is 12 font pixels and a margin of 2 above and below, 32 rows at scale 2
    CHECK(dark(plain, 0, 32) == 0);
    CHECK(std::equal(plain.rgb.begin() + 32 * 96 * 3, plain.rgb.end(), labelled.rgb.begin() + 32 * 96 * 3));  // below the band
    Image cut = plain;
    draw_label(cut, std::string(200, 'W') + "\n\x01", 3);  // longer than the panel, control bytes: cut, no overrun
    CHECK(cut.rgb.size() == plain.rgb.size());
}

TEST_CASE("ellicast render refuses an output that is not a PNG and one that would overwrite its input") {
    if (!test::have_sample("meshes/woody.obj")) return;
    auto dir = test::scratch_dir("render_cli");
    const std::string exe = test::ellicast_exe().string();
    const std::string model = (test::shared_samples() / "meshes/woody.obj").string();
    CHECK(std::system((exe + " render " + model + " -o " + (dir / "w.jpg").string() + " 2>/dev/null").c_str()) != 0);
    CHECK(std::system((exe + " render " + model + " -o " + model + " 2>/dev/null").c_str()) != 0);
    CHECK(std::system((exe + " render " + model + " --width 64 --height 64 -o " + (dir / "w.png").string() +
                       " 2>/dev/null").c_str()) == 0);
    CHECK(std::filesystem::file_size(dir / "w.png") > 100);
    // Labels: one a panel.
    CHECK(std::system((exe + " render " + model + " " + model + " --labels one -o " + (dir / "l.png").string() + " 2>/dev/null").c_str()) != 0);
    CHECK(std::system((exe + " render " + model + " " + model + " --width 64 --height 64 --labels 'one,two' -o " + (dir / "l.png").string() +
                       " 2>/dev/null").c_str()) == 0);
}
