// One strip visit of the active list: every active triangle's rows of the strip, in submission
// order, each retired as it is drawn (its slot to the free list when it ends in the strip, else
// kept in the order, compacted). Runs of consecutive lanes triangles go to one call (LaneRun,
// core/span/lane_rows.hpp): on Armv7E-M the hand-allocated loop takes a run's triangles one
// after the other without coming back here, which is most of a visit's cost when triangles are
// about a pixel and visit a strip for a row or two.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/strip_rows.hpp"
#include "lineraster/core/span/lane_rows.hpp"

namespace lr {

// The strip loop's active list: order[0, count) the active slots in submission order,
// free_slots[0, free) the unused ones.
struct ActiveList {
  uint16_t* order;
  uint16_t* free_slots;
  const ActiveTriangle* active;
  size_t count;
  size_t free;
};

// Visits the strip sr: triangles whose rows are `lanes` (nullptr: none) in runs through
// run(t, r, sr), the others through their rows. Leaves in `list` the kept triangles and the free
// slots. r: the run's words (the strip loop keeps them in its object, not on the stack, whose
// deepest path goes through the visit).
template <class Run>
[[gnu::always_inline]] inline void visit_active(ActiveList& list, StripRows& sr, RowFn lanes,
                                                LaneRun& r, Run&& run) {
  uint16_t* const order = list.order;
  uint16_t* const free_slots = list.free_slots;
  const ActiveTriangle* const active = list.active;
  const size_t count = list.count;
  const int32_t last = sr.y_last;
  size_t kept = 0, free = list.free;
  for (size_t i = 0; i < count;) {
    const uint16_t slot = order[i];
    const ActiveTriangle& t = active[slot];
    if (lanes != nullptr && t.rows == lanes) {
      r.start(order + i, order + kept, free_slots + free, order + count, active, lanes, last);
      run(t, r, sr);
      i = static_cast<size_t>(r.next - order);
      kept = static_cast<size_t>(r.kept - order);
      free = static_cast<size_t>(r.free - free_slots);
      continue;
    }
    t.rows(t, sr);
    if (t.last_row <= last)
      free_slots[free++] = slot;
    else
      order[kept++] = slot;
    ++i;
  }
  list.count = kept;
  list.free = free;
}

}  // namespace lr
