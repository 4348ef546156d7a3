// A region of interest (the paper's closing claim: points can be inserted in any order, so a
// receiver may refine only what the viewer looks at and hold the other points until the view turns
// to them). A box, or what a camera sees: the cone around its line of sight, from its position
// through its target, with half the field of view as half-angle (widened to the frame's corners
// by the aspect ratio). Coordinates are the model's world space (glTF: after node transforms).
#pragma once

#include <array>
#include <string>

namespace ellicast {

struct Region {
    enum class Kind { Box, View } kind = Kind::Box;
    std::array<double, 3> min{}, max{};          // Box
    std::array<double, 3> eye{}, target{};       // View
    double fov_degrees = 45, aspect = 1;         // View: vertical field of view, width / height

    static Region box(const std::array<double, 3>& lo, const std::array<double, 3>& hi);
    static Region view(const std::array<double, 3>& eye, const std::array<double, 3>& target, double fov_degrees,
                       double aspect = 1);
    // Empty when the region is usable, else what is wrong with it (an inverted box, a camera whose
    // target is its position, a field of view outside (0, 180) degrees, a value that is not finite).
    std::string problem() const;
    bool contains(const std::array<double, 3>& p) const;
    std::string describe() const;
};

}  // namespace ellicast
