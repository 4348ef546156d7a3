// Pictures of meshes: a small software rasterizer (z-buffer, Lambert shading with a head light,
// optional wireframe) writing PNG files, so that reconstructions can be looked at, not only measured.
#pragma once

#include "ellicast/codec/mesh.h"

#include <array>
#include <string>
#include <vector>

namespace ellicast {

struct RenderOptions {
    int width = 480;          // pixels per panel
    int height = 480;
    double azimuth = 35;      // degrees around the vertical (+Y) axis
    double elevation = 20;    // degrees above the horizontal plane
    bool wireframe = false;   // draw triangle edges
    bool use_colors = true;   // vertex colours when the mesh has them, else a neutral grey
    int supersample = 2;      // rendered at this factor and averaged down (anti-aliasing)
};

// An RGB image, row-major from the top row.
struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
};

// Renders `meshes` (drawn together) framed by the box [lo, hi], seen from the options' direction
// with an orthographic camera.
Image render_meshes(const std::vector<Mesh>& meshes, const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                    const RenderOptions& options);

// The bounding box of every position of `meshes`.
void bounding_box(const std::vector<Mesh>& meshes, std::array<double, 3>& lo, std::array<double, 3>& hi);

// Places images side by side (same height), separated by a thin white gutter.
Image side_by_side(const std::vector<Image>& panels);

// Writes `text` (printable ASCII; other bytes shown as '?') in dark grey on a light band across the
// top of `image`, `scale` pixels a font pixel (stb_easy_font's 6-pixel-high glyphs); cut at the
// image's right edge.
void draw_label(Image& image, const std::string& text, int scale = 2);

// Writes a PNG; throws std::runtime_error naming the file when it cannot.
void write_png(const std::string& path, const Image& image);

}  // namespace ellicast
