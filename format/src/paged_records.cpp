// PointRecords: packing a quantized point record into 16-bit components and back.
#include "ellicast/format/paged_records.h"

#include <stdexcept>
#include <string>

namespace ellicast {

void PointRecords::set_layout(const ObjectInfo& object) {
    if (!records_.empty()) return;
    normal_ = object.has(kAttrNormal);
    texcoord_ = object.has(kAttrTexcoord);
    channels_ = object.color_channels();
    records_.set_stride(3 + (normal_ ? 2 : 0) + (texcoord_ ? 2 : 0) + size_t(channels_));
}

bool PointRecords::insert(uint32_t index, const QuantizedPoint& q) {
    std::array<uint16_t, kAll> record{};
    size_t n = 0;
    // Every bit depth is at most 16 (spec 5.3), so each component fits.
    for (uint32_t v : q.position) record[n++] = uint16_t(v);
    if (normal_)
        for (uint32_t v : q.normal) record[n++] = uint16_t(v);
    if (texcoord_)
        for (uint32_t v : q.texcoord) record[n++] = uint16_t(v);
    for (int c = 0; c < channels_; ++c) record[n++] = uint16_t(q.color[size_t(c)]);
    return records_.insert(index, record.data());
}

QuantizedPoint PointRecords::unpack(const uint16_t* record) const {
    QuantizedPoint q;
    for (uint32_t& v : q.position) v = *record++;
    if (normal_)
        for (uint32_t& v : q.normal) v = *record++;
    if (texcoord_)
        for (uint32_t& v : q.texcoord) v = *record++;
    for (int c = 0; c < channels_; ++c) q.color[size_t(c)] = *record++;
    return q;
}

std::optional<QuantizedPoint> PointRecords::find(uint32_t index) const {
    const uint16_t* record = records_.find(index);
    if (!record) return std::nullopt;
    return unpack(record);
}

QuantizedPoint PointRecords::at(uint32_t index) const {
    const uint16_t* record = records_.find(index);
    if (!record) throw std::out_of_range("no record held for point " + std::to_string(index));
    return unpack(record);
}

}  // namespace ellicast
