#pragma once
// Internal: the map from a Delaunay facet (its sorted vertex ids) to a value, as FacetCache
// (restricted_facets.h) keeps one per facet whose Voronoi edge crosses Sigma. Every insertion erases the
// facets of its conflict region and every update adds the new ones, tens of lookups per point:
// with std::unordered_map each is a chain of cache misses (bucket, then node), and these lookups
// sit on the path of every insertion of the refinement loop. This table
// is open addressing with linear probing (keys and a value index in one 16-byte slot, deletion
// by backward shift, so no tombstones); the values live in a deque, so pointers to them stay
// valid until their own key is erased, as with std::unordered_map's nodes.
#include "delaunay/delaunay.h"

#include <cstdint>
#include <deque>
#include <utility>
#include <vector>

namespace isodel::mesher {

template <class Value>
class FacetTable {
public:
    /// The value of \p key, inserting \p value first when absent; second: whether it was.
    std::pair<Value*, bool> try_emplace(const FacetKey& key, const Value& value)
    {
        if (2 * (size_ + 1) > slots_.size()) grow();
        std::size_t i = home(key);
        for (; slots_[i].index != kEmpty; i = (i + 1) & mask_)
            if (slots_[i].key == key) return {&values_[slots_[i].index], false};
        std::uint32_t index;
        if (free_.empty()) {
            index = std::uint32_t(values_.size());
            values_.push_back(value);
        } else {
            index = free_.back();
            free_.pop_back();
            values_[index] = value;
        }
        slots_[i] = Slot{key, index};
        ++size_;
        return {&values_[index], true};
    }

    /// The value of \p key, or null. Read-only: safe from several threads while nothing writes.
    const Value* find(const FacetKey& key) const
    {
        if (size_ == 0) return nullptr;
        for (std::size_t i = home(key);; i = (i + 1) & mask_) {
            if (slots_[i].index == kEmpty) return nullptr;
            if (slots_[i].key == key) return &values_[slots_[i].index];
        }
    }

    /// Whether \p key is present. Read-only: safe from several threads while nothing writes.
    bool contains(const FacetKey& key) const { return find(key) != nullptr; }

    /// Removes \p key; false when it was absent.
    bool erase(const FacetKey& key)
    {
        if (size_ == 0) return false;
        std::size_t i = home(key);
        for (;; i = (i + 1) & mask_) {
            if (slots_[i].index == kEmpty) return false;
            if (slots_[i].key == key) break;
        }
        free_.push_back(slots_[i].index);
        --size_;
        // Backward shift: move later members of the probe run into the hole when their home
        // slot is not cyclically in (hole, their slot].
        for (std::size_t j = i;;) {
            j = (j + 1) & mask_;
            if (slots_[j].index == kEmpty) break;
            const std::size_t k = home(slots_[j].key);
            const bool stays = i <= j ? (i < k && k <= j) : (i < k || k <= j);
            if (stays) continue;
            slots_[i] = slots_[j];
            i = j;
        }
        slots_[i].index = kEmpty;
        return true;
    }

    void clear()
    {
        slots_.clear();
        values_.clear();
        free_.clear();
        size_ = 0;
        mask_ = 0;
    }

    std::size_t size() const { return size_; }

private:
    static constexpr std::uint32_t kEmpty = 0xffffffffu;
    struct Slot {
        FacetKey key;
        std::uint32_t index = kEmpty;
    };

    std::size_t home(const FacetKey& k) const
    {
        std::uint64_t h = FacetKeyHash()(k);
        h ^= h >> 33; // murmur3's finaliser: every key bit reaches the low (mask) bits
        h *= 0xff51afd7ed558ccdull;
        h ^= h >> 33;
        return std::size_t(h) & mask_;
    }

    void grow()
    {
        std::vector<Slot> old;
        old.swap(slots_);
        slots_.assign(old.empty() ? 1024 : 2 * old.size(), Slot());
        mask_ = slots_.size() - 1;
        for (const Slot& s : old)
            if (s.index != kEmpty) {
                std::size_t i = home(s.key);
                while (slots_[i].index != kEmpty) i = (i + 1) & mask_;
                slots_[i] = s;
            }
    }

    std::vector<Slot> slots_;
    std::deque<Value> values_;
    std::vector<std::uint32_t> free_;
    std::size_t size_ = 0;
    std::size_t mask_ = 0;
};

} // namespace isodel::mesher
