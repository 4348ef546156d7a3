// Cameras and punctual lights (format 1.10): the records that CAMERA and LIGHT packets carry, their
// payloads and checks. Follows spec/format.md section 26 (Format 1.10 addition: cameras and punctual
// lights): 26.2 CAMERA payload; 26.3 LIGHT payload. The SCENE node record's camera and light fields
// (26.1) are SceneNode::camera and SceneNode::light, in scene.h; what a receiver keeps of them is in
// received_stream.h.
#pragma once

#include "ellicast/format/error.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast {

enum class CameraProjection : uint8_t { Perspective = 0, Orthographic = 1 };

// A glTF camera (spec 26.2). Perspective: `a` is aspectRatio (0: none), `b` is yfov, zfar 0 is
// infinite. Orthographic: `a` is xmag, `b` is ymag.
struct SceneCamera {
    uint16_t index = 0;
    uint16_t camera_count = 0;  // size of the whole camera table
    CameraProjection projection = CameraProjection::Perspective;
    float a = 0, b = 0, znear = 0, zfar = 0;
    std::string name;
    bool operator==(const SceneCamera&) const = default;  // floats as numbers: +0 and -0 agree
};
inline constexpr size_t kCameraFixedSize = 24;

enum class LightType : uint8_t { Directional = 0, Point = 1, Spot = 2 };

// A KHR_lights_punctual light (spec 26.3). range 0: none (infinite); cone angles 0 but for spots.
struct SceneLight {
    uint16_t index = 0;
    uint16_t light_count = 0;  // size of the whole light table
    LightType type = LightType::Directional;
    std::array<float, 3> color{1, 1, 1};
    float intensity = 1;
    float range = 0;
    float inner_cone = 0, outer_cone = 0;
    std::string name;
    bool operator==(const SceneLight&) const = default;
};
inline constexpr size_t kLightFixedSize = 36;

// The value rules of spec 26.2 (steps 3..6) and 26.3 (steps 3..7) on a record's fields: whether a
// receiver takes it. (The length and index rules are the decoder's.)
bool valid_camera(const SceneCamera& camera);
bool valid_light(const SceneLight& light);

// Names longer than 255 bytes are cut at a UTF-8 boundary.
std::vector<uint8_t> encode_camera_payload(const SceneCamera& camera);
Error decode_camera_payload(std::span<const uint8_t> payload, SceneCamera& out);
std::vector<uint8_t> encode_light_payload(const SceneLight& light);
Error decode_light_payload(std::span<const uint8_t> payload, SceneLight& out);

}  // namespace ellicast
