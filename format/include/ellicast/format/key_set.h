// A set of 64-bit keys with open addressing (linear probing), grown by doubling at half load: the
// exact layer's edge table and the encoder's occupied cells. Keys must not be UINT64_MAX.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ellicast {

class KeySet {
public:
    // True when `key` was not in the set (it is now).
    bool insert(uint64_t key) {
        if (2 * (count_ + 1) > slots_.size()) rehash(std::max<size_t>(16, 2 * slots_.size()));
        const bool fresh = place(slots_, key);
        count_ += fresh;
        return fresh;
    }
    bool contains(uint64_t key) const {
        if (slots_.empty()) return false;
        const size_t mask = slots_.size() - 1;
        for (size_t i = hash(key) & mask;; i = (i + 1) & mask) {
            if (slots_[i] == key) return true;
            if (slots_[i] == kEmpty) return false;
        }
    }
    // Empties the set, keeping its room.
    void clear() {
        std::fill(slots_.begin(), slots_.end(), kEmpty);
        count_ = 0;
    }

private:
    static constexpr uint64_t kEmpty = UINT64_MAX;
    static size_t hash(uint64_t x) {  // the splitmix64 finalizer
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
        return size_t(x ^ (x >> 31));
    }
    // Puts key into slots (a power of two long, never full); false when it was there.
    static bool place(std::vector<uint64_t>& slots, uint64_t key) {
        const size_t mask = slots.size() - 1;
        for (size_t i = hash(key) & mask;; i = (i + 1) & mask) {
            if (slots[i] == key) return false;
            if (slots[i] == kEmpty) {
                slots[i] = key;
                return true;
            }
        }
    }
    void rehash(size_t size) {
        std::vector<uint64_t> slots(size, kEmpty);
        for (uint64_t key : slots_)
            if (key != kEmpty) place(slots, key);
        slots_ = std::move(slots);
    }
    std::vector<uint64_t> slots_;
    size_t count_ = 0;
};

}  // namespace ellicast
