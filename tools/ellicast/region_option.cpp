// The region of interest options (region_option.h).
#include "region_option.h"

#include "ellicast/converters/asset.h"

#include <sstream>

namespace ellicast::cli {

bool parse_region(const std::string& text, Region& out, std::string& error) {
    const auto colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    std::vector<double> v;
    if (colon != std::string::npos) {
        std::stringstream items(text.substr(colon + 1));
        std::string item;
        while (std::getline(items, item, ',')) {
            try {
                size_t used = 0;
                v.push_back(std::stod(item, &used));
                if (used != item.size()) throw std::invalid_argument("trailing");
            } catch (const std::exception&) {
                error = "--region \"" + text + "\": \"" + item + "\" is not a number";
                return false;
            }
        }
    }
    if (kind == "box" && v.size() == 6) {
        out = Region::box({v[0], v[1], v[2]}, {v[3], v[4], v[5]});
    } else if (kind == "view" && (v.size() == 7 || v.size() == 8)) {
        out = Region::view({v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v.size() == 8 ? v[7] : 1.0);
    } else {
        error = "--region \"" + text + "\": expected box:X0,Y0,Z0,X1,Y1,Z1 or view:EX,EY,EZ,TX,TY,TZ,FOV[,ASPECT]";
        return false;
    }
    if (std::string problem = out.problem(); !problem.empty()) {
        error = "--region \"" + text + "\": " + problem;
        return false;
    }
    return true;
}

std::function<bool(size_t, const std::array<float, 3>&)> region_filter(const Region& region,
                                                                        const ReceivedStream& stream) {
    // The scene alone: every object empty, so nothing is decoded to build it.
    const Asset scene = received_asset(stream, std::vector<Mesh>(stream.objects().size()));
    auto transforms = object_world_transforms(scene);
    return [region, transforms = std::move(transforms)](size_t object, const std::array<float, 3>& p) {
        if (object >= transforms.size() || transforms[object].empty()) return true;
        for (const auto& m : transforms[object]) {
            const std::array<double, 3> world = {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12],
                                                 m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
                                                 m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
            if (region.contains(world)) return true;
        }
        return false;
    };
}

}  // namespace ellicast::cli
