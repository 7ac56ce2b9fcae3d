#pragma once
// A first-in first-out queue whose slots keep their objects: pushBack() hands out a slot as the
// element that last used it left it (its vectors and strings with their storage), and popFront() only
// marks the slot free. A steady-state loop of push and pop therefore allocates nothing once the queue
// has held its most elements; the caller resets what it refills. Growth (a push into a full queue)
// keeps every object too.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/error.h"

namespace penumbra {

template <typename T>
class RecyclingQueue {
public:
    bool empty() const { return count_ == 0; }
    size_t size() const { return count_; }
    T& front() { PENUMBRA_ASSERT(count_ > 0); return slots_[first_]; }
    T& back() { PENUMBRA_ASSERT(count_ > 0); return slots_[(first_ + count_ - 1) % slots_.size()]; }
    T& operator[](size_t i) { PENUMBRA_ASSERT(i < count_); return slots_[(first_ + i) % slots_.size()]; }

    // The new last element: a recycled slot (reset what you refill) or, when every slot is taken, a
    // new default-constructed one.
    T& pushBack() {
        if (count_ == slots_.size()) {
            std::rotate(slots_.begin(), slots_.begin() + std::ptrdiff_t(first_), slots_.end());  // swaps: storage kept
            first_ = 0;
            slots_.emplace_back();
        }
        ++count_;
        return back();
    }
    void popFront() {
        PENUMBRA_ASSERT(count_ > 0);
        first_ = (first_ + 1) % slots_.size();
        --count_;
    }
    void popBack() {
        PENUMBRA_ASSERT(count_ > 0);
        --count_;
    }
    // Removes element i, keeping the order of the others (its slot moves to the free end).
    void erase(size_t i) {
        PENUMBRA_ASSERT(i < count_);
        for (size_t j = i; j + 1 < count_; ++j) std::swap((*this)[j], (*this)[j + 1]);
        --count_;
    }

private:
    std::vector<T> slots_;
    size_t first_ = 0, count_ = 0;
};

}  // namespace penumbra
