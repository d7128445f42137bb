// The edge table: one list head per strip (its bucket), linked through the binned triangles in
// submission order, so that the strip loop finds the triangles that start in a strip without
// sorting. With strip signatures (strip_inputs.hpp) it also holds each strip's input signature.
//
// classify() is the binner's test of a triangle (facing, area, rows and columns it covers);
// add() puts a classified triangle into the bucket of its first strip.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/binning/outcome.hpp"
#include "lineraster/core/binning/strip_inputs.hpp"
#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

class EdgeTable {
 public:
  // Takes the stores for a viewport of `height` rows in strips of `strip_height`: false when
  // the buckets (one per strip) or the signatures (none, or two per strip) do not fit, or when
  // the triangle colours (none, or one per triangle) are fewer than the triangles.
  bool configure(std::span<BinnedTriangle> triangles, std::span<TriangleColors> colors,
                 std::span<uint16_t> buckets, std::span<uint32_t> strip_inputs, int width,
                 int height, int strip_height) {
    const int strips = (height + strip_height - 1) / strip_height;
    if (buckets.size() < static_cast<size_t>(strips)) return false;
    if (!strip_inputs.empty() && strip_inputs.size() < 2 * static_cast<size_t>(strips))
      return false;
    if (!colors.empty() && colors.size() < triangles.size()) return false;
    triangles_ =
        triangles.size() > kMaxStoreEntries - 1 ? triangles.first(kMaxStoreEntries - 1) : triangles;
    colors_ = colors.empty() ? colors : colors.first(triangles_.size());
    buckets_ = buckets;
    strip_inputs_ = strip_inputs;
    width_ = width;
    height_ = height;
    strip_height_ = strip_height;
    strip_reciprocal_ = ((1u << 17) + static_cast<uint32_t>(strip_height) - 1) /
                        static_cast<uint32_t>(strip_height);
    strips_ = strips;
    return true;
  }

  // Empties every bucket; with signatures, starts each strip's from the frame's. The row window
  // is the viewport, no band is binned.
  void begin_frame(uint32_t frame_signature) {
    frame_signature_ = frame_signature;
    empty(0, strips_);
    window_ = {0, height_ - 1, false, false, 0};
  }
  // Binning a band of strips [s0, s1) (docs/bands.md): empties the store and every bucket; with
  // signatures, restarts those of strips [s0, s1); the row window is the band's rows.
  void begin_band(int s0, int s1) {
    empty(s0, s1);
    const int end = s1 * strip_height_ < height_ ? s1 * strip_height_ : height_;
    window_ = {s0 * strip_height_, end - 1, true, false, 0};
  }

  // The row window: the rows of the band being binned. Outside bands it is the viewport (and
  // classify() clamps to that already). banding(): a band is binned (or the frame's first one,
  // once the store filled up: start_banding()).
  bool banding() const { return window_.banding; }
  void start_banding() { window_.banding = true; }
  int32_t window_first() const { return window_.r0; }
  int32_t window_last() const { return window_.r1; }
  // Whether rows [r0, r1] are all outside the window (a band's triangle of another band).
  bool outside_window(int32_t r0, int32_t r1) const {
    return window_.banding && (r1 < window_.r0 || r0 > window_.r1);
  }
  // Rows [r0, r1] clamped to the window.
  void clamp_to_window(int32_t& r0, int32_t& r1) const {
    if (r0 < window_.r0) r0 = window_.r0;
    if (r1 > window_.r1) r1 = window_.r1;
  }
  // The strip after the window's last.
  int window_end() const { return window_.r1 / strip_height_ + 1; }
  // A triangle added whose first row is above the window: counted in its own band.
  void note_carried(int32_t first_row) {
    if (window_.banding && first_row < window_.r0) ++window_.carried;
  }
  uint32_t carried() const { return window_.carried; }
  // The window is one strip and a triangle did not fit: it was dropped.
  bool dropped() const { return window_.dropped; }
  void set_dropped() { window_.dropped = true; }
  // The table full while a band is binned: the window ends at a strip boundary above, evicting
  // the triangles that start below it (keeping the strips whose triangles fill up to 3/4 of the
  // store, at least the first). vertices: the store the triangles refer to (their first rows);
  // mark: as evict_from(); in_window: the count of evicted triangles that started in the
  // window (the others were carried). False when the window is one strip.
  bool shrink_window(std::span<const ScreenVertex> vertices, size_t& mark, uint32_t& in_window);

  // The binner's tests: kBinned when the triangle would be binned (capacity aside), with its
  // first and last row (clamped to the viewport) in r0, r1. Facing first (most culled triangles
  // leave there: facing() below). classify() out of line for the rare paths; classify_inline()
  // where a loop wants it in its body.
  [[gnu::always_inline]] Outcome classify_inline(const ScreenVertex& v0, const ScreenVertex& v1,
                                                 const ScreenVertex& v2, Cull cull, int32_t& r0,
                                                 int32_t& r1) const;
  Outcome classify(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                   Cull cull, int32_t& r0, int32_t& r1) const;
  // classify()'s tests after the facing: whether the triangle's bounds hold a pixel centre of
  // the viewport, its first row (clamped) in r0, its last in *r1 when not nullptr. With kExact,
  // bounds of one centre hold it only when the triangle covers it (holds_centre); without, a
  // triangle of one row may still miss its one centre: misses_its_centre() says (the C lane
  // calls it out of line, which keeps its loop's registers).
  template <bool kExact = false>
  [[gnu::always_inline]] bool covers(const ScreenVertex& v0, const ScreenVertex& v1,
                                     const ScreenVertex& v2, int32_t& r0,
                                     int32_t* r1 = nullptr) const;
  // Whether the triangle's bounds hold one pixel centre of the viewport (one_centre) that it
  // does not cover (holds_centre): off the hot paths (a triangle of one row).
  bool misses_its_centre(const ScreenVertex& v0, const ScreenVertex& v1,
                         const ScreenVertex& v2) const;

 private:
  // A triangle's candidate pixel centres: rows [r0, r1] and columns [c0, c1), r0 and c0
  // clamped at 0, r1 and c1 not clamped (covers() and misses_its_centre() share them).
  struct Bounds {
    int32_t r0, r1, c0, c1;
  };
  [[gnu::always_inline]] static Bounds bounds(const ScreenVertex& v0, const ScreenVertex& v1,
                                              const ScreenVertex& v2);

 public:
  bool full() const { return count_ >= triangles_.size(); }
  size_t capacity() const { return triangles_.size(); }
  size_t bucket_size(int strip) const {
    size_t n = 0;
    for (uint16_t i = buckets_[static_cast<size_t>(strip)]; i != kNoTriangle;
         i = triangles_[i].next)
      ++n;
    return n;
  }

  // Removes the triangles of the buckets of strips >= cut (evicted(t) is called for each) and
  // closes the gaps, keeping the others (and their colours) in submission order: strip_of(t)
  // gives the strip of a kept triangle, whose bucket is rebuilt. `mark` (an index into the
  // store, or size()) becomes the new index of the first kept triangle at or after it.
  template <class StripOf, class Evicted>
  void evict_from(int cut, size_t& mark, StripOf&& strip_of, Evicted&& evicted) {
    for (int s = cut; s < strips_; ++s) {
      uint16_t& head = buckets_[static_cast<size_t>(s)];
      for (uint16_t i = head; i != kNoTriangle;) {
        const uint16_t next = triangles_[i].next;
        triangles_[i].next = kEvicted;
        i = next;
      }
      head = kNoTriangle;
    }
    for (int s = 0; s < cut; ++s) buckets_[static_cast<size_t>(s)] = kNoTriangle;
    size_t out = 0, new_mark = 0;
    for (size_t i = 0; i < count_; ++i) {
      if (i == mark) new_mark = out;
      BinnedTriangle t = triangles_[i];
      if (t.next == kEvicted) {
        evicted(t);
        continue;
      }
      uint16_t& head = buckets_[static_cast<size_t>(strip_of(t))];
      t.next = head;
      head = static_cast<uint16_t>(out);
      if (!colors_.empty()) colors_[out] = colors_[i];
      triangles_[out++] = t;
    }
    mark = mark >= count_ ? out : new_mark;
    count_ = out;
  }

  // Appends without a check each (the front end's lane): the count and the room in registers,
  // written back by finish(). Nothing else may add to the table until then.
  class Run {
   public:
    explicit Run(EdgeTable& table)
        : table_(table), count_(table.count_), end_(table.triangles_.size()) {}
    bool full() const { return count_ >= end_; }
    // As EdgeTable::add(); not full().
    BinnedTriangle& add(int32_t r0) {
      const auto index = static_cast<uint16_t>(count_++);
      BinnedTriangle& t = table_.triangles_[index];
      uint16_t& head = table_.buckets_[table_.strip_of_row(r0)];
      t.next = head;
      head = index;
      return t;
    }
    void finish() { table_.count_ = count_; }

   private:
    EdgeTable& table_;
    size_t count_, end_;
  };

  // The same for a hand-written appender (the front end's lane on Armv7E-M): the arrays, the
  // strip reciprocal (strip_of_row), the count and the room; set_size() writes the count back.
  struct Raw {
    BinnedTriangle* triangles;
    uint16_t* buckets;
    uint32_t strip_reciprocal;
    uint32_t count, capacity;
  };
  Raw raw() {
    return {triangles_.data(), buckets_.data(), strip_reciprocal_, static_cast<uint32_t>(count_),
            static_cast<uint32_t>(triangles_.size())};
  }
  void set_size(size_t count) { count_ = count; }

  // Appends a triangle to the bucket of the strip of row r0 and returns it for the caller to
  // fill in (its `next` is set here). Not full().
  [[gnu::always_inline]] BinnedTriangle& add(int32_t r0) {
    const auto index = static_cast<uint16_t>(count_++);
    BinnedTriangle& t = triangles_[index];
    uint16_t& head = buckets_[strip_of_row(r0)];
    t.next = head;
    head = index;
    return t;
  }

  // The strip of row r (0 <= r < 4096): r / strip_height as (r m) >> 17 with
  // m = ceil(2^17 / strip_height): exact for r < 2^17 / 32 (the error of m, below
  // strip_height <= 32, times r stays below 2^17; tests/core/math_test.cpp), and no division on
  // cores without a divider.
  size_t strip_of_row(int32_t r) const {
    return static_cast<size_t>((static_cast<uint32_t>(r) * strip_reciprocal_) >> 17);
  }

  // The colours of the triangle add() returned last. has_colors().
  void set_colors(const TriangleColors& c) { colors_[count_ - 1] = c; }
  bool has_colors() const { return !colors_.empty(); }

  // Mixes a triangle's signature into those of the strips of rows [r0, r1]. signing().
  void sign(int32_t r0, int32_t r1, uint32_t triangle_signature) {
    for (int32_t s = r0 / strip_height_; s <= r1 / strip_height_; ++s) {
      uint32_t& sig = strip_inputs_[static_cast<size_t>(s)];
      InputHash hs(sig);
      hs.add(triangle_signature);
      sig = hs.value();
    }
  }

  bool signing() const { return !strip_inputs_.empty(); }
  size_t size() const { return count_; }
  int strips() const { return strips_; }
  std::span<BinnedTriangle> triangles() const { return triangles_.first(count_); }
  std::span<const TriangleColors> colors() const {
    return colors_.empty() ? colors_ : colors_.first(count_);
  }
  std::span<uint16_t> buckets() const { return buckets_.first(static_cast<size_t>(strips_)); }
  std::span<uint32_t> strip_inputs() const { return strip_inputs_; }

 private:
  // A triangle's `next` while evict_from() removes it (no index is this large: configure()).
  static constexpr uint16_t kEvicted = kNoTriangle - 1;

  void empty(int s0, int s1) {
    count_ = 0;
    for (int i = 0; i < strips_; ++i) buckets_[static_cast<size_t>(i)] = kNoTriangle;
    if (signing())
      for (int i = s0; i < s1; ++i) strip_inputs_[static_cast<size_t>(i)] = frame_signature_;
  }

  struct Window {
    int32_t r0, r1;    // the rows
    bool banding;      // a band is binned
    bool dropped;      // the window is one strip and dropped triangles
    uint32_t carried;  // the band's triangles from above it
  };
  Window window_{0, 0, false, false, 0};

  std::span<BinnedTriangle> triangles_{};
  std::span<TriangleColors> colors_{};
  std::span<uint16_t> buckets_{};
  std::span<uint32_t> strip_inputs_{};
  int width_ = 0, height_ = 0, strip_height_ = 0, strips_ = 0;
  uint32_t strip_reciprocal_ = 0;  // ceil(2^17 / strip_height) (strip_of_row)
  size_t count_ = 0;
  uint32_t frame_signature_ = 0;
};

// Whether the one pixel centre (c, r) of the viewport that a triangle's bounds hold, c and r
// both at least 1 (one_centre), is covered by it by the raster rules (docs/raster-rules.md):
// a centre on an edge belongs to the triangle on the edge's right, or above a horizontal
// bottom edge, as the row loop's columns give it. Such bounds put every vertex within 256
// subpixels of the centre on each axis: the edge functions' products stay below 2^19.
constexpr bool holds_centre(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                            int32_t c, int32_t r) {
  const int32_t xc = c * kSubpixel + kHalfPixel, yc = r * kSubpixel + kHalfPixel;
  // Inside, every edge function is negative when twice the signed area is (a front face's);
  // the other winding is the same triangle with two vertices swapped.
  const bool swap = (v1.x - v0.x) * (v2.y - v0.y) - (v2.x - v0.x) * (v1.y - v0.y) > 0;
  const ScreenVertex* const v[3] = {&v0, swap ? &v2 : &v1, swap ? &v1 : &v2};
  for (int i = 0; i < 3; ++i) {
    const ScreenVertex& a = *v[i];
    const ScreenVertex& b = *v[i == 2 ? 0 : i + 1];
    const int32_t dx = b.x - a.x, dy = b.y - a.y;
    const int32_t e = dx * (yc - a.y) - dy * (xc - a.x);
    // On the edge: in when the inside lies right of it (dy > 0) or above it (dy = 0, dx > 0).
    if (e >= (dy > 0 || (dy == 0 && dx > 0) ? 1 : 0)) return false;
  }
  return true;
}
// The binner tests the one pixel centre of bounds that hold one (one_centre, holds_centre),
// except where code size comes first (-Os: 0.4 KB): there setup_rows, which makes every
// triangle's rows at -Os, finds those slivers exactly (counted without pixels, not culled).
#if defined(__OPTIMIZE_SIZE__)
inline constexpr bool kOneCentreTest = false;
#else
inline constexpr bool kOneCentreTest = true;
#endif
// Whether bounds whose rows are [a, b) and columns [c0, c1) (a and c0 clamped at 0, b and c1
// not clamped) hold one pixel centre, away from row 0 and column 0 (where the clamp may have
// cut larger bounds): then the binner tests that centre exactly (holds_centre).
constexpr bool one_centre(int32_t a, int32_t b, int32_t c0, int32_t c1) {
  return kOneCentreTest && b - a == 1 && c1 - c0 == 1 && a != 0 && c0 != 0;
}

// The facing of a triangle from its edge deltas (v1 - v0, v2 - v0; subpixels, below 2^23 inside
// the guard band): 2 front-facing, 1 back-facing, 0 no area, from the sign of twice the signed
// area, exact: 32-bit products on cores without a 64-bit product when every delta is in
// [-2^15, 2^15) (products within [-2^30 + 2^15, 2^30], their difference inside int32), else
// 64-bit ones (each below 2^46).
[[gnu::always_inline]] inline uint32_t facing(int32_t dx1, int32_t dy1, int32_t dx2, int32_t dy2) {
  if (kSplitWideProducts &&
      ((static_cast<uint32_t>(dx1 + 0x8000) | static_cast<uint32_t>(dy1 + 0x8000) |
        static_cast<uint32_t>(dx2 + 0x8000) | static_cast<uint32_t>(dy2 + 0x8000)) >>
       16) == 0) {
    const int32_t area = dx1 * dy2 - dx2 * dy1;
    return front_facing(area) ? 2u : back_facing(area) ? 1u : 0u;
  }
  const int64_t area = mul_wide(dx1, dy2) - mul_wide(dx2, dy1);
  return front_facing(area) ? 2u : back_facing(area) ? 1u : 0u;
}

inline EdgeTable::Bounds EdgeTable::bounds(const ScreenVertex& v0, const ScreenVertex& v1,
                                           const ScreenVertex& v2) {
  int32_t ymin = v0.y < v1.y ? v0.y : v1.y, ymax = v0.y > v1.y ? v0.y : v1.y;
  ymin = v2.y < ymin ? v2.y : ymin;
  ymax = v2.y > ymax ? v2.y : ymax;
  int32_t xmin = v0.x < v1.x ? v0.x : v1.x, xmax = v0.x > v1.x ? v0.x : v1.x;
  xmin = v2.x < xmin ? v2.x : xmin;
  xmax = v2.x > xmax ? v2.x : xmax;
  Bounds k{first_row_below(ymin), last_row_at_or_above(ymax),
           // Columns whose centres can pass both edge tests: [ceil((xmin-128)/256),
           // ceil((xmax-128)/256)).
           (xmin - kHalfPixel + kSubpixel - 1) >> kSubpixelBits,
           (xmax - kHalfPixel + kSubpixel - 1) >> kSubpixelBits};
  if (k.r0 < 0) k.r0 = 0;
  if (k.c0 < 0) k.c0 = 0;
  return k;
}

template <bool kExact>
inline bool EdgeTable::covers(const ScreenVertex& v0, const ScreenVertex& v1,
                              const ScreenVertex& v2, int32_t& r0, int32_t* r1_out) const {
  Bounds k = bounds(v0, v1, v2);
  r0 = k.r0;
  if (kExact && k.r1 == k.r0 && one_centre(k.r0, k.r1 + 1, k.c0, k.c1) && k.r0 < height_ &&
      k.c0 < width_) {
    if (r1_out != nullptr) *r1_out = k.r1;
    return holds_centre(v0, v1, v2, k.c0, k.r0);
  }
  if (k.r1 > height_ - 1) k.r1 = height_ - 1;
  if (k.c1 > width_) k.c1 = width_;
  if (r1_out != nullptr) *r1_out = k.r1;
  return k.r0 <= k.r1 && k.c0 < k.c1;
}

inline Outcome EdgeTable::classify_inline(const ScreenVertex& v0, const ScreenVertex& v1,
                                          const ScreenVertex& v2, Cull cull, int32_t& r0,
                                          int32_t& r1) const {
  const uint32_t f = facing(v1.x - v0.x, v1.y - v0.y, v2.x - v0.x, v2.y - v0.y);
  if (f == 0) return Outcome::kZeroArea;
  if ((cull == Cull::kBack && f == 1) || (cull == Cull::kFront && f == 2))
    return Outcome::kBackface;
  return covers<true>(v0, v1, v2, r0, &r1) ? Outcome::kBinned : Outcome::kOffscreen;
}

}  // namespace lr
