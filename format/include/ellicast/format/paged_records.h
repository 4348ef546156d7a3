// Per-point records a receiver holds (points, mapped records not placed yet, skin influences, morph
// displacements), by point index, in memory near what they cost on the wire. A std::map node per
// record cost about 90 bytes beside the record: an honest 1M-point mapped stream (2 bytes a point on
// the wire) was held in 45 times its bytes. Here records live in pages of 512 point indices, made
// when a record of theirs arrives: a bit per index held and the records of the page side by side in
// index order. Serves the receiver's byte budget (spec/format.md 11.6).
#pragma once

#include "ellicast/format/bits.h"
#include "ellicast/format/quantize.h"
#include "ellicast/format/stream_info.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace ellicast {

// Records of `stride` elements of E each, by point index.
template <class E>
class PagedRecords {
public:
    static constexpr uint32_t kPagePoints = 512;

private:
    struct Page {
        std::array<uint64_t, kPagePoints / 64> held{};
        std::vector<E> values;  // the records of the held indices, in index order
    };
    // A page's map node and its bookkeeping.
    static constexpr uint64_t kPageCost = sizeof(Page) + 48;
    static bool held(const Page& page, uint32_t bit) { return (page.held[bit / 64] >> (bit % 64)) & 1; }
    // Records of the page before `bit`.
    static size_t rank(const Page& page, uint32_t bit) {
        size_t n = 0;
        for (uint32_t w = 0; w < bit / 64; ++w) n += ones(page.held[w]);
        if (bit % 64) n += ones(page.held[bit / 64] << (64 - bit % 64));
        return n;
    }

public:
    PagedRecords() = default;
    explicit PagedRecords(size_t stride) : stride_(stride) {}
    size_t stride() const { return stride_; }
    // The record size; only while nothing is held (records held keep theirs otherwise).
    void set_stride(size_t stride) {
        if (size_ == 0) stride_ = stride;
    }
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    bool contains(uint32_t index) const { return find(index) != nullptr; }
    // The first element of the record of point `index`, or nullptr when none is held. Valid until
    // the next insert or erase.
    const E* find(uint32_t index) const {
        auto p = pages_.find(index / kPagePoints);
        if (p == pages_.end() || !held(p->second, index % kPagePoints)) return nullptr;
        return p->second.values.data() + rank(p->second, index % kPagePoints) * stride_;
    }
    // Keeps the record (stride() elements from `record`) of a point not held yet; returns false,
    // changing nothing, when one is held.
    bool insert(uint32_t index, const E* record) {
        auto [p, fresh] = pages_.try_emplace(index / kPagePoints);
        if (fresh) memory_ += kPageCost;
        Page& page = p->second;
        const uint32_t bit = index % kPagePoints;
        if (held(page, bit)) return false;
        const size_t before = page.values.capacity();
        page.values.insert(page.values.begin() + std::ptrdiff_t(rank(page, bit) * stride_), record, record + stride_);
        page.held[bit / 64] |= uint64_t{1} << (bit % 64);
        ++size_;
        if (page.values.size() == size_t{kPagePoints} * stride_) page.values.shrink_to_fit();  // full: no room for growth
        memory_ = memory_ - before * sizeof(E) + page.values.capacity() * sizeof(E);
        return true;
    }
    bool erase(uint32_t index) {
        auto p = pages_.find(index / kPagePoints);
        const uint32_t bit = index % kPagePoints;
        if (p == pages_.end() || !held(p->second, bit)) return false;
        Page& page = p->second;
        const auto at = page.values.begin() + std::ptrdiff_t(rank(page, bit) * stride_);
        page.values.erase(at, at + std::ptrdiff_t(stride_));
        page.held[bit / 64] &= ~(uint64_t{1} << (bit % 64));
        --size_;
        if (page.values.empty()) {
            memory_ -= kPageCost + page.values.capacity() * sizeof(E);
            pages_.erase(p);
        }
        return true;
    }
    // What the held records cost: their pages, elements (as allocated) and bookkeeping.
    uint64_t memory() const { return memory_; }
    // How many indices in [from, to) hold a record, counted from the pages' bits.
    size_t count(uint64_t from, uint64_t to) const {
        size_t n = 0;
        if (from >= to) return 0;
        for (auto p = pages_.lower_bound(uint32_t(from / kPagePoints));
             p != pages_.end() && uint64_t(p->first) * kPagePoints < to; ++p) {
            const uint64_t base = uint64_t(p->first) * kPagePoints;
            const uint32_t lo = from > base ? uint32_t(from - base) : 0;
            const uint32_t hi = uint32_t(std::min<uint64_t>(to - base, kPagePoints));
            n += rank(p->second, hi) - rank(p->second, lo);
        }
        return n;
    }

    // Iterates (index, first element of its record) in index order.
    class const_iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = std::pair<uint32_t, const E*>;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = value_type;
        value_type operator*() const {
            return {page_->first * kPagePoints + bit_, page_->second.values.data() + rank_ * owner_->stride_};
        }
        const_iterator& operator++() {
            ++bit_, ++rank_;
            settle();
            return *this;
        }
        bool operator==(const const_iterator& o) const { return page_ == o.page_ && bit_ == o.bit_; }

    private:
        friend class PagedRecords;
        using PageIt = typename std::map<uint32_t, Page>::const_iterator;
        const_iterator(const PagedRecords* owner, PageIt page, uint32_t bit, size_t rank)
            : owner_(owner), page_(page), bit_(bit), rank_(rank) {
            settle();
        }
        // Forward to the next held index (or the end).
        void settle() {
            while (page_ != owner_->pages_.end()) {
                while (bit_ < kPagePoints) {
                    const uint64_t rest = page_->second.held[bit_ / 64] >> (bit_ % 64);
                    if (rest != 0) {
                        bit_ += uint32_t(std::countr_zero(rest));
                        return;
                    }
                    bit_ = (bit_ / 64 + 1) * 64;
                }
                ++page_, bit_ = 0, rank_ = 0;
            }
            bit_ = 0;
        }
        const PagedRecords* owner_;
        PageIt page_;
        uint32_t bit_;
        size_t rank_;  // records of the page before bit_
    };
    const_iterator begin() const { return const_iterator(this, pages_.begin(), 0, 0); }
    const_iterator end() const { return const_iterator(this, pages_.end(), 0, 0); }
    // The first held index >= `index`.
    const_iterator lower_bound(uint32_t index) const {
        auto p = pages_.lower_bound(index / kPagePoints);
        if (p == pages_.end() || p->first != index / kPagePoints) return const_iterator(this, p, 0, 0);
        return const_iterator(this, p, index % kPagePoints, rank(p->second, index % kPagePoints));
    }

private:
    std::map<uint32_t, Page> pages_;  // by page number (index / kPagePoints)
    size_t stride_ = 1;
    size_t size_ = 0;
    uint64_t memory_ = 0;
};

// An object's quantized point records by index: each component the object's records carry (spec
// 7.1: position, and normal, texture coordinates and colour when its attributes say so) as 16 bits
// (every bit depth is at most 16). Components a record does not carry read back as 0. Iterates
// (index, QuantizedPoint) in index order.
class PointRecords {
public:
    PointRecords() : records_(kAll) {}
    // The components records of `object` carry; only while nothing is held.
    void set_layout(const ObjectInfo& object);
    size_t size() const { return records_.size(); }
    bool empty() const { return records_.empty(); }
    bool contains(uint32_t index) const { return records_.contains(index); }
    std::optional<QuantizedPoint> find(uint32_t index) const;
    // The record of point `index`; std::out_of_range when none is held.
    QuantizedPoint at(uint32_t index) const;
    // Keeps the record of a point not held yet; false (changing nothing) when one is held.
    bool insert(uint32_t index, const QuantizedPoint& q);
    bool erase(uint32_t index) { return records_.erase(index); }
    uint64_t memory() const { return records_.memory(); }
    // How many indices in [from, to) hold a record.
    size_t count(uint64_t from, uint64_t to) const { return records_.count(from, to); }

    class const_iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = std::pair<uint32_t, QuantizedPoint>;
        using difference_type = std::ptrdiff_t;
        using pointer = void;
        using reference = value_type;
        value_type operator*() const {
            auto [index, record] = *it_;
            return {index, owner_->unpack(record)};
        }
        const_iterator& operator++() {
            ++it_;
            return *this;
        }
        bool operator==(const const_iterator& o) const { return it_ == o.it_; }

    private:
        friend class PointRecords;
        const_iterator(const PointRecords* owner, PagedRecords<uint16_t>::const_iterator it) : owner_(owner), it_(it) {}
        const PointRecords* owner_;
        PagedRecords<uint16_t>::const_iterator it_;
    };
    const_iterator begin() const { return {this, records_.begin()}; }
    const_iterator end() const { return {this, records_.end()}; }
    const_iterator lower_bound(uint32_t index) const { return {this, records_.lower_bound(index)}; }

private:
    static constexpr size_t kAll = 3 + 2 + 2 + 4;
    QuantizedPoint unpack(const uint16_t* record) const;
    bool normal_ = true, texcoord_ = true;
    int channels_ = 4;
    PagedRecords<uint16_t> records_;
};

}  // namespace ellicast
