// The region of interest options (`decode --region`, the live view's camera): parsing the text
// form, and the filter that holds the points outside the region, object by object, through the
// world transforms of the nodes that show each object.
#pragma once

#include "ellicast/codec/region.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace ellicast {
class ReceivedStream;
}

namespace ellicast::cli {

// "box:X0,Y0,Z0,X1,Y1,Z1" or "view:EX,EY,EZ,TX,TY,TZ,FOV[,ASPECT]" (world coordinates; the field of
// view in degrees). False with `error` naming what is wrong.
bool parse_region(const std::string& text, Region& out, std::string& error);

// True for a point (object index, position in the object's frame) that some node showing the
// object puts inside `region`; an object no node shows is always inside. The transforms come
// from the stream's scene (format 1.1), the identity without one.
std::function<bool(size_t, const std::array<float, 3>&)> region_filter(const Region& region,
                                                                        const ReceivedStream& stream);

}  // namespace ellicast::cli
