// The baseline a broadcast engineer would build next (issue 28): ellicast's base (its STREAM_INFO and
// ELLIPSOIDS packets) repeated for a first picture, and every other slot an MDS-coded Draco symbol.
// A receiver shows the ellipsoids' surface as soon as it holds the stream info and an ellipsoid
// packet, and the exact Draco model once every Draco block holds k symbols.
#pragma once

#include "ellicast/compare/ellicast_scheme.h"
#include "ellicast/compare/schemes.h"

#include <string>
#include <vector>

namespace ellicast::compare {

class EllipsoidsDracoMds : public Scheme {
public:
    // Copies the base packets of `ellicast` and every packet of `mds` (decoding goes through both
    // schemes, so they must outlive this one). The base takes `ellicast`'s base share of the slots in
    // whole rounds of its order: a STREAM_INFO part before each ELLIPSOIDS packet, so that a receiver
    // needs two base slots in a row for its first picture (ellicast's own carousel repeats the stream
    // info every 8 packets).
    EllipsoidsDracoMds(const EllicastScheme& ellicast, const DracoMds& mds);

    std::string name() const override { return "ellipsoids+draco-mds"; }
    std::string describe() const override;
    uint64_t period() const override { return period_; }
    uint32_t packet_at(uint64_t n) const override;
    bool reconstruct(const std::vector<uint32_t>& held, Mesh& out) const override;
    bool can_show(const std::vector<uint32_t>& held) const override;
    bool complete(const std::vector<uint32_t>& held) const override;
    // The exact model once Draco decodes, else what the base packets held give.
    std::vector<uint32_t> outcome_key(const std::vector<uint32_t>& held) const override;
    double data_fraction(const std::vector<uint32_t>& held) const override;
    size_t base_slots() const { return base_slots_; }

private:
    // held -> (indices into the ellicast scheme's packets, indices into the MDS scheme's packets)
    void split(const std::vector<uint32_t>& held, std::vector<uint32_t>& base, std::vector<uint32_t>& mds) const;

    const EllicastScheme& ellicast_;
    const DracoMds& mds_;
    std::vector<uint32_t> base_;   // our packet i < base_.size(): ellicast packet base_[i]
    std::vector<uint32_t> order_;  // the base's round robin (our indices): a STREAM_INFO before each ELLIPSOIDS
    uint64_t period_ = 0, base_slots_ = 0;
};

}  // namespace ellicast::compare
