// Software rasterizer for PNG pictures of meshes (see render.h).
#include "ellicast/converters/render.h"
#include "ellicast/format.h"

#include <stb_easy_font.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace ellicast {

namespace {

using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 normalized(const Vec3& a) {
    double l = std::sqrt(dot(a, a));
    return l > 0 ? Vec3{a[0] / l, a[1] / l, a[2] / l} : Vec3{0, 0, 1};
}

// Camera basis: `forward` points from the eye into the scene.
struct Camera {
    Vec3 right, up, forward, center;
    double scale;  // pixels per model unit
    double cx, cy;
};

Camera make_camera(const Vec3& lo, const Vec3& hi, const RenderOptions& o, int w, int h) {
    const double pi = std::acos(-1.0);
    double az = o.azimuth * pi / 180, el = o.elevation * pi / 180;
    Vec3 eye_dir = {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};  // towards the eye
    Camera c;
    c.forward = {-eye_dir[0], -eye_dir[1], -eye_dir[2]};
    c.right = normalized(cross(c.forward, Vec3{0, 1, 0}));
    c.up = cross(c.right, c.forward);
    c.center = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    double radius = 0.5 * std::sqrt(dot(sub(hi, lo), sub(hi, lo)));
    c.scale = radius > 0 ? 0.92 * std::min(w, h) / (2 * radius) : 1;
    c.cx = w / 2.0;
    c.cy = h / 2.0;
    return c;
}

}  // namespace

void bounding_box(const std::vector<Mesh>& meshes, std::array<double, 3>& lo, std::array<double, 3>& hi) {
    lo = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    hi = {-lo[0], -lo[1], -lo[2]};
    for (const auto& m : meshes)
        for (const auto& p : m.positions)
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
    if (lo[0] > hi[0]) lo = {0, 0, 0}, hi = {1, 1, 1};
}

Image render_meshes(const std::vector<Mesh>& meshes, const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                    const RenderOptions& options) {
    const int ss = std::clamp(options.supersample, 1, 4);
    const int w = std::clamp(options.width, 16, 8192) * ss, h = std::clamp(options.height, 16, 8192) * ss;
    const Camera cam = make_camera(lo, hi, options, w, h);
    std::vector<float> depth(size_t(w) * h, std::numeric_limits<float>::infinity());
    std::vector<float> color(size_t(w) * h * 3);
    for (size_t i = 0; i < size_t(w) * h; ++i) {  // a soft vertical gradient background
        double t = double(i / w) / h;
        for (int k = 0; k < 3; ++k) color[i * 3 + k] = float(0.97 - 0.12 * t);
    }
    const Vec3 light = normalized({-cam.forward[0] + 0.3 * cam.up[0] - 0.2 * cam.right[0],
                                   -cam.forward[1] + 0.3 * cam.up[1] - 0.2 * cam.right[1],
                                   -cam.forward[2] + 0.3 * cam.up[2] - 0.2 * cam.right[2]});
    const double edge_px = 0.7 * ss;

    for (const Mesh& mesh : meshes) {
        const bool colored = options.use_colors && mesh.colors.size() == mesh.positions.size();
        std::vector<Vec3> screen(mesh.positions.size());
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            Vec3 d = sub({mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2]}, cam.center);
            screen[i] = {cam.cx + dot(d, cam.right) * cam.scale, cam.cy - dot(d, cam.up) * cam.scale, dot(d, cam.forward)};
        }
        if (mesh.triangles.empty()) {  // a point set: small squares
            for (size_t i = 0; i < screen.size(); ++i) {
                int x0 = int(screen[i][0]), y0 = int(screen[i][1]);
                for (int y = y0 - ss; y <= y0 + ss; ++y)
                    for (int x = x0 - ss; x <= x0 + ss; ++x) {
                        if (x < 0 || y < 0 || x >= w || y >= h) continue;
                        size_t p = size_t(y) * w + x;
                        if (screen[i][2] >= depth[p]) continue;
                        depth[p] = float(screen[i][2]);
                        for (int k = 0; k < 3; ++k)
                            color[p * 3 + k] = colored ? float(std::pow(std::clamp(double(mesh.colors[i][k]), 0.0, 1.0), 1 / 2.2))
                                                       : 0.25f;
                    }
            }
            continue;
        }
        for (const auto& t : mesh.triangles) {
            if (t[0] >= screen.size() || t[1] >= screen.size() || t[2] >= screen.size()) continue;
            const Vec3 &a = screen[t[0]], &b = screen[t[1]], &c = screen[t[2]];
            const auto &pa = mesh.positions[t[0]], &pb = mesh.positions[t[1]], &pc = mesh.positions[t[2]];
            Vec3 n = normalized(cross(sub({pb[0], pb[1], pb[2]}, {pa[0], pa[1], pa[2]}),
                                      sub({pc[0], pc[1], pc[2]}, {pa[0], pa[1], pa[2]})));
            double shade = 0.18 + 0.82 * std::fabs(dot(n, light));  // two-sided: open meshes show their inside
            double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            if (std::fabs(area) < 1e-12) continue;
            int x0 = std::max(0, int(std::floor(std::min({a[0], b[0], c[0]}))));
            int x1 = std::min(w - 1, int(std::ceil(std::max({a[0], b[0], c[0]}))));
            int y0 = std::max(0, int(std::floor(std::min({a[1], b[1], c[1]}))));
            int y1 = std::min(h - 1, int(std::ceil(std::max({a[1], b[1], c[1]}))));
            // Distances from a pixel to each edge, in pixels, for the wireframe.
            double la = std::hypot(c[0] - b[0], c[1] - b[1]), lb = std::hypot(a[0] - c[0], a[1] - c[1]),
                   lc = std::hypot(b[0] - a[0], b[1] - a[1]);
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    double px = x + 0.5, py = y + 0.5;
                    double w0 = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
                    double w1 = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
                    double w2 = 1 - w0 - w1;
                    if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                    double z = w0 * a[2] + w1 * b[2] + w2 * c[2];
                    size_t p = size_t(y) * w + x;
                    if (z >= depth[p]) continue;
                    depth[p] = float(z);
                    std::array<double, 3> base{0.55, 0.58, 0.63};
                    if (colored)
                        for (int k = 0; k < 3; ++k)
                            base[k] = w0 * mesh.colors[t[0]][k] + w1 * mesh.colors[t[1]][k] + w2 * mesh.colors[t[2]][k];
                    bool edge = options.wireframe &&
                                std::min({w0 * std::fabs(area) / la, w1 * std::fabs(area) / lb, w2 * std::fabs(area) / lc}) <
                                    edge_px;
                    // Shading happens in linear light (glTF colours are linear); the PNG holds sRGB.
                    for (int k = 0; k < 3; ++k)
                        color[p * 3 + k] = float(std::pow(std::clamp(base[k] * shade * (edge ? 0.35 : 1.0), 0.0, 1.0), 1 / 2.2));
                }
        }
    }
    Image img;
    img.width = w / ss;
    img.height = h / ss;
    img.rgb.resize(size_t(img.width) * img.height * 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int k = 0; k < 3; ++k) {
                double sum = 0;
                for (int dy = 0; dy < ss; ++dy)
                    for (int dx = 0; dx < ss; ++dx) sum += color[(size_t(y * ss + dy) * w + (x * ss + dx)) * 3 + k];
                img.rgb[(size_t(y) * img.width + x) * 3 + k] =
                    uint8_t(std::clamp(sum / (ss * ss), 0.0, 1.0) * 255 + 0.5);
            }
    return img;
}

Image side_by_side(const std::vector<Image>& panels) {
    Image out;
    const int gutter = 6;
    for (const auto& p : panels) out.height = std::max(out.height, p.height);
    for (size_t i = 0; i < panels.size(); ++i) out.width += panels[i].width + (i ? gutter : 0);
    out.rgb.assign(size_t(out.width) * out.height * 3, 255);
    int x0 = 0;
    for (const auto& p : panels) {
        for (int y = 0; y < p.height; ++y)
            std::copy_n(p.rgb.begin() + size_t(y) * p.width * 3, size_t(p.width) * 3,
                        out.rgb.begin() + (size_t(y) * out.width + x0) * 3);
        x0 += p.width + gutter;
    }
    return out;
}

void draw_label(Image& image, const std::string& text, int scale) {
    if (text.empty() || image.width <= 0 || image.height <= 0 || scale < 1) return;
    std::string shown = text;
    for (char& c : shown)
        if (c < 32 || c > 126) c = '?';
    // A light band behind the text, as high as a line and its margins.
    const int margin = 2 * scale;
    const int band = std::min(image.height, 12 * scale + 2 * margin);
    for (int y = 0; y < band; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int k = 0; k < 3; ++k) {
                uint8_t& v = image.rgb[(size_t(y) * image.width + x) * 3 + k];
                v = uint8_t((v + 3 * 245) / 4);
            }
    // stb_easy_font gives quads (4 vertices of x, y, z, colour: 16 bytes each), 6 units a line.
    std::vector<char> quads(std::max<size_t>(4096, shown.size() * 300));
    const int count = stb_easy_font_print(0, 0, shown.data(), nullptr, quads.data(), int(quads.size()));
    for (int q = 0; q < count; ++q) {
        float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
        for (int corner = 0; corner < 4; ++corner) {
            float xy[2];
            std::memcpy(xy, quads.data() + size_t(q) * 64 + corner * 16, sizeof xy);
            for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], xy[k]), hi[k] = std::max(hi[k], xy[k]);
        }
        const int x0 = margin + int(std::lround(lo[0] * scale)), y0 = margin + int(std::lround(lo[1] * scale));
        const int x1 = margin + int(std::lround(hi[0] * scale)), y1 = margin + int(std::lround(hi[1] * scale));
        for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
            for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x)
                for (int k = 0; k < 3; ++k) image.rgb[(size_t(y) * image.width + x) * 3 + k] = 40;
    }
}

void write_png(const std::string& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0) throw std::runtime_error(path + ": empty image");
    // Encoded in memory, written through write_file (a private temporary, then a rename).
    std::vector<uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, image.rgb.data(), image.width * 3))
        throw std::runtime_error(path + ": cannot encode the PNG file");
    std::string message;
    if (write_file(path, png, message) != Error::Ok) throw std::runtime_error("cannot write " + message);
}

}  // namespace ellicast
