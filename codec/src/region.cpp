// A region of interest: a box or a camera's view cone (region.h).
#include "ellicast/codec/region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ellicast {

Region Region::box(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
    Region r;
    r.kind = Kind::Box;
    r.min = lo;
    r.max = hi;
    return r;
}

Region Region::view(const std::array<double, 3>& eye, const std::array<double, 3>& target, double fov_degrees,
                    double aspect) {
    Region r;
    r.kind = Kind::View;
    r.eye = eye;
    r.target = target;
    r.fov_degrees = fov_degrees;
    r.aspect = aspect;
    return r;
}

std::string Region::problem() const {
    auto finite = [](const std::array<double, 3>& v) {
        return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
    };
    if (kind == Kind::Box) {
        if (!finite(min) || !finite(max)) return "a box corner is not a finite number";
        for (int k = 0; k < 3; ++k)
            if (min[k] > max[k]) return "the box's minimum corner is above its maximum on axis " + std::string(1, "xyz"[k]);
        return {};
    }
    if (!finite(eye) || !finite(target)) return "the camera's position or target is not a finite number";
    if (eye == target) return "the camera's target is its position: it looks nowhere";
    if (!(fov_degrees > 0 && fov_degrees < 180)) return "the field of view must be between 0 and 180 degrees";
    if (!(aspect > 0 && aspect < 100)) return "the aspect ratio must be between 0 and 100";
    return {};
}

bool Region::contains(const std::array<double, 3>& p) const {
    if (kind == Kind::Box)
        return p[0] >= min[0] && p[0] <= max[0] && p[1] >= min[1] && p[1] <= max[1] && p[2] >= min[2] && p[2] <= max[2];
    double d[3], v[3];
    for (int k = 0; k < 3; ++k) {
        d[k] = target[k] - eye[k];
        v[k] = p[k] - eye[k];
    }
    const double dd = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double vv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (vv == 0) return true;
    const double along = (d[0] * v[0] + d[1] * v[1] + d[2] * v[2]) / dd;
    if (along <= 0) return false;
    // Half-angle to the frame's corner: tan = tan(fov/2) * sqrt(1 + aspect^2).
    const double t = std::tan(fov_degrees * M_PI / 360.0) * std::sqrt(1 + aspect * aspect);
    const double across = std::sqrt(std::max(0.0, vv * vv - along * along));
    return across <= t * along;
}

std::string Region::describe() const {
    char text[256];
    if (kind == Kind::Box)
        std::snprintf(text, sizeof text, "the box (%g, %g, %g) .. (%g, %g, %g)", min[0], min[1], min[2], max[0], max[1],
                      max[2]);
    else
        std::snprintf(text, sizeof text, "the view from (%g, %g, %g) to (%g, %g, %g), %g degrees", eye[0], eye[1], eye[2],
                      target[0], target[1], target[2], fov_degrees);
    return text;
}

}  // namespace ellicast
