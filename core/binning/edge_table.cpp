#include "lineraster/core/binning/edge_table.hpp"

namespace lr {

Outcome EdgeTable::classify(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                            Cull cull, int32_t& r0, int32_t& r1) const {
  const int64_t area = signed_area2(v0, v1, v2);
  if (area == 0) return Outcome::kZeroArea;
  const bool front = front_facing(area);
  if ((cull == Cull::kBack && !front) || (cull == Cull::kFront && front)) return Outcome::kBackface;
  int32_t ymin = v0.y < v1.y ? v0.y : v1.y, ymax = v0.y > v1.y ? v0.y : v1.y;
  ymin = v2.y < ymin ? v2.y : ymin;
  ymax = v2.y > ymax ? v2.y : ymax;
  int32_t xmin = v0.x < v1.x ? v0.x : v1.x, xmax = v0.x > v1.x ? v0.x : v1.x;
  xmin = v2.x < xmin ? v2.x : xmin;
  xmax = v2.x > xmax ? v2.x : xmax;
  r0 = first_row_below(ymin);
  r1 = last_row_at_or_above(ymax);
  if (r0 < 0) r0 = 0;
  if (r1 > height_ - 1) r1 = height_ - 1;
  // Columns whose centres can pass both edge tests: [ceil((xmin-128)/256),
  // ceil((xmax-128)/256)).
  int32_t c0 = (xmin - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
  int32_t c1 = (xmax - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
  if (c0 < 0) c0 = 0;
  if (c1 > width_) c1 = width_;
  if (r0 > r1 || c0 >= c1) return Outcome::kOffscreen;
  return Outcome::kBinned;
}

}  // namespace lr
