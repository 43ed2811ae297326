#pragma once
// The reference's broad phase (reference_pd.h).
#include <vector>

namespace pd {
namespace reference {

// Sort-and-sweep over boxes sorted by x0: calls on_pair(a, b) for every pair
// whose x ranges overlap; on_pair tests the other axes and returns true to stop.
template <typename Box, typename OnPair>
void SweepPairs(const std::vector<Box>& a, const std::vector<Box>& b, std::vector<int>* active_a,
                std::vector<int>* active_b, OnPair&& on_pair) {
  active_a->clear();
  active_b->clear();
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const bool take_a = j >= b.size() || (i < a.size() && a[i].x0 <= b[j].x0);
    const Box& box = take_a ? a[i] : b[j];
    std::vector<int>& others = take_a ? *active_b : *active_a;
    const std::vector<Box>& other_boxes = take_a ? b : a;
    for (size_t k = 0; k < others.size();) {
      const Box& o = other_boxes[others[k]];
      if (o.x1 < box.x0) {  // ended before this one starts: never overlaps again
        others[k] = others.back();
        others.pop_back();
        continue;
      }
      if (take_a ? on_pair(box, o) : on_pair(o, box)) return;
      ++k;
    }
    if (take_a) {
      active_a->push_back(static_cast<int>(i++));
    } else {
      active_b->push_back(static_cast<int>(j++));
    }
  }
}

}  // namespace reference
}  // namespace pd
