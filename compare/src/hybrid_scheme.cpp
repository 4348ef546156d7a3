// ellipsoids+draco-mds: ellicast's base at its carousel share, draco-mds everywhere else.
#include "ellicast/compare/hybrid_scheme.h"

#include "ellicast/format.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ellicast::compare {

EllipsoidsDracoMds::EllipsoidsDracoMds(const EllicastScheme& ellicast, const DracoMds& mds)
    : ellicast_(ellicast), mds_(mds) {
    const auto& e = ellicast.packets();
    for (uint32_t i = 0; i < e.size(); ++i) {
        const uint8_t type = e[i].size() > 6 ? e[i][6] : 0;
        if (type == static_cast<uint8_t>(PacketType::StreamInfo) || type == static_cast<uint8_t>(PacketType::Ellipsoids)) {
            base_.push_back(i);
            packets_.push_back(e[i]);
        }
    }
    if (base_.empty()) throw CompareError("ellipsoids+draco-mds: the ellicast stream has no base packets");
    std::vector<uint32_t> infos, ellipsoids;
    for (uint32_t i = 0; i < base_.size(); ++i)
        (packets_[i][6] == static_cast<uint8_t>(PacketType::StreamInfo) ? infos : ellipsoids).push_back(i);
    for (size_t k = 0; k < ellipsoids.size(); ++k) {
        if (!infos.empty()) order_.push_back(infos[k % infos.size()]);
        order_.push_back(ellipsoids[k]);
    }
    for (size_t k = ellipsoids.size(); k < infos.size(); ++k) order_.push_back(infos[k]);  // parts left over
    packets_.insert(packets_.end(), mds.packets().begin(), mds.packets().end());
    // One period: the MDS schedule's period and a whole number of rounds of the base, about the
    // carousel's base share of the slots.
    const double share = std::clamp(ellicast.base_share(), 0.0, 0.9);
    const double wanted = double(mds.period()) * share / (1 - share);
    const uint64_t rounds = std::max<uint64_t>(1, uint64_t(std::llround(wanted / double(order_.size()))));
    base_slots_ = rounds * order_.size();
    period_ = mds.period() + base_slots_;
}

std::string EllipsoidsDracoMds::describe() const {
    std::ostringstream s;
    s << "ellicast's base (" << base_.size() << " STREAM_INFO and ELLIPSOIDS packets, a STREAM_INFO before each "
      << "ELLIPSOIDS) in " << base_slots_ << " of every "
      << period_ << " slots (" << std::llround(100.0 * double(base_slots_) / double(period_))
      << "%, spread evenly), draco-mds (" << mds_.packets().size()
      << " symbols) in the others: the ellipsoids' surface until the Draco file decodes, then the exact model";
    return s.str();
}

uint32_t EllipsoidsDracoMds::packet_at(uint64_t n) const {
    const uint64_t q = n / period_, r = n % period_;
    // Base slots spread evenly over the period: slot r is a base slot when the count steps there.
    const uint64_t before = r * base_slots_ / period_, after = (r + 1) * base_slots_ / period_;
    if (after > before) return order_[(q * base_slots_ + before) % order_.size()];
    const uint64_t mds_slot = q * (period_ - base_slots_) + (r - before);
    return uint32_t(base_.size() + mds_.packet_at(mds_slot));
}

void EllipsoidsDracoMds::split(const std::vector<uint32_t>& held, std::vector<uint32_t>& base,
                               std::vector<uint32_t>& mds) const {
    for (uint32_t i : held) {
        if (i < base_.size()) base.push_back(base_[i]);
        else mds.push_back(uint32_t(i - base_.size()));
    }
    std::sort(base.begin(), base.end());
}

bool EllipsoidsDracoMds::reconstruct(const std::vector<uint32_t>& held, Mesh& out) const {
    std::vector<uint32_t> base, mds;
    split(held, base, mds);
    if (mds_.complete(mds)) return mds_.reconstruct(mds, out);
    return ellicast_.reconstruct(base, out);
}

bool EllipsoidsDracoMds::can_show(const std::vector<uint32_t>& held) const {
    std::vector<uint32_t> base, mds;
    split(held, base, mds);
    return mds_.complete(mds) || ellicast_.can_show(base);
}

bool EllipsoidsDracoMds::complete(const std::vector<uint32_t>& held) const {
    std::vector<uint32_t> base, mds;
    split(held, base, mds);
    return mds_.complete(mds);
}

std::vector<uint32_t> EllipsoidsDracoMds::outcome_key(const std::vector<uint32_t>& held) const {
    std::vector<uint32_t> base, mds;
    split(held, base, mds);
    if (mds_.complete(mds)) return {UINT32_MAX};
    return base;
}

double EllipsoidsDracoMds::data_fraction(const std::vector<uint32_t>& held) const {
    std::vector<uint32_t> base, mds;
    split(held, base, mds);
    return mds_.data_fraction(mds);
}

}  // namespace ellicast::compare
