// Writes the bundled sample models of samples/: procedural, so the project ships only what it makes.
//
//   trefoil.obj  a closed genus-1 tube around a trefoil knot, with texture coordinates (seams where
//                the parameterization wraps: positions are shared, UVs are per corner) and per-vertex
//                colours ("v x y z r g b"), 3,240 vertices, 6,480 triangles.
//
// Usage: make_samples OUTPUT_DIR
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace {

using Vec = std::array<double, 3>;

Vec sub(Vec a, Vec b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(Vec a, Vec b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
Vec normalized(Vec a) {
    double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return {a[0] / l, a[1] / l, a[2] / l};
}

// The (2,3) torus knot.
Vec knot(double t) {
    double r = 2 + std::cos(3 * t);
    return {r * std::cos(2 * t), r * std::sin(2 * t), std::sin(3 * t)};
}

bool write_trefoil(const std::string& path) {
    const int along = 180, around = 18;
    const double tube = 0.55;
    const double pi = std::acos(-1.0);
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fprintf(f, "# ellicast sample: tube around a trefoil knot (samples/make_samples.cpp)\n");
    for (int i = 0; i < along; ++i) {
        double t = 2 * pi * i / along, h = 1e-4;
        Vec c = knot(t);
        Vec tangent = normalized(sub(knot(t + h), knot(t - h)));
        // Frenet frame: the trefoil's curvature never vanishes, and the frame closes on itself.
        Vec accel = sub(sub(knot(t + h), c), sub(c, knot(t - h)));
        Vec binormal = normalized(cross(tangent, accel));
        Vec normal = cross(binormal, tangent);
        for (int j = 0; j < around; ++j) {
            double a = 2 * pi * j / around;
            Vec p;
            for (int k = 0; k < 3; ++k) p[k] = c[k] + tube * (std::cos(a) * normal[k] + std::sin(a) * binormal[k]);
            double hue = static_cast<double>(i) / along;
            double r = 0.5 + 0.5 * std::cos(2 * pi * hue), g = 0.5 + 0.5 * std::cos(2 * pi * (hue - 1.0 / 3)),
                   b = 0.5 + 0.5 * std::cos(2 * pi * (hue - 2.0 / 3));
            std::fprintf(f, "v %.6f %.6f %.6f %.4f %.4f %.4f\n", p[0], p[1], p[2], r, g, b);
        }
    }
    for (int i = 0; i <= along; ++i)
        for (int j = 0; j <= around; ++j)
            std::fprintf(f, "vt %.6f %.6f\n", 4.0 * i / along, static_cast<double>(j) / around);
    auto v = [&](int i, int j) { return (i % along) * around + (j % around) + 1; };
    auto vt = [&](int i, int j) { return i * (around + 1) + j + 1; };
    for (int i = 0; i < along; ++i)
        for (int j = 0; j < around; ++j) {
            // Counter-clockwise seen from outside: normals point out of the tube.
            std::fprintf(f, "f %d/%d %d/%d %d/%d\n", v(i, j), vt(i, j), v(i + 1, j + 1), vt(i + 1, j + 1), v(i + 1, j),
                         vt(i + 1, j));
            std::fprintf(f, "f %d/%d %d/%d %d/%d\n", v(i, j), vt(i, j), v(i, j + 1), vt(i, j + 1), v(i + 1, j + 1),
                         vt(i + 1, j + 1));
        }
    return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_samples OUTPUT_DIR\n");
        return 2;
    }
    std::string dir = argv[1];
    if (!write_trefoil(dir + "/trefoil.obj")) {
        std::fprintf(stderr, "make_samples: cannot write %s/trefoil.obj\n", dir.c_str());
        return 3;
    }
    std::fprintf(stderr, "wrote %s/trefoil.obj\n", dir.c_str());
    return 0;
}
