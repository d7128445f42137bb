// Test harness: a Renderer with host-allocated storage and a capture display, plus helpers to
// give each triangle its own identifying colour so coverage can be read back per pixel.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/raster/renderer.hpp"
#include "host_sim/emulator/capture_display.hpp"
#include "tests/reference/ref_renderer.hpp"

namespace lr::test {

template <int K = 8, class PF = Rgb888>
class CoreHarness {
 public:
  CoreHarness(int width, int height, size_t max_vertices = 0xFFFF, size_t max_triangles = 0xFFFE,
              size_t max_active = 1024, size_t max_draws = 64)
      : width_(width),
        height_(height),
        vertices_(max_vertices),
        triangles_(max_triangles),
        draws_(max_draws),
        buckets_(static_cast<size_t>((height + K - 1) / K)),
        active_(max_active),
        active_index_(2 * max_active),
        depth_(static_cast<size_t>(width) * K),
        surfaces_(max_vertices),
        tables_(4 * lighting_table_words(kMaxLightingTable, true)),
        pixel_lights_(16),
        display_(static_cast<size_t>(width) * K),
        renderer_(std::make_unique<Renderer<PF, K>>()) {
    FrameStorage s{vertices_,     triangles_, draws_,    buckets_, active_,
                   active_index_, depth_,     surfaces_, tables_,  pixel_lights_};
    configured_ = renderer_->configure(s, width, height);
  }
  Status configured() const { return configured_; }
  Renderer<PF, K>& renderer() { return *renderer_; }
  Status begin(Rgb8 background = {0, 0, 0}, const Camera& cam = {}, const LightSet& lights = {}) {
    return renderer_->begin_frame(cam, lights, background);
  }
  // Renders and returns the frame as 8-bit RGB.
  host::ImageRgb8 render(Status* status = nullptr) {
    depth_capture_.resize(width_, height_);
    Status s = renderer_->render(display_, &depth_capture_);
    if (status) *status = s;
    return display_.image();
  }
  const std::vector<uint16_t>& depth() const { return depth_capture_.depth(); }
  const host::CaptureDisplay<PF>& display() const { return display_; }

 private:
  int width_, height_;
  std::vector<ScreenVertex> vertices_;
  std::vector<BinnedTriangle> triangles_;
  std::vector<DrawRecord> draws_;
  std::vector<uint16_t> buckets_;
  std::vector<ActiveTriangle> active_;
  std::vector<uint16_t> active_index_;
  std::vector<uint16_t> depth_;
  std::vector<SurfaceVertex> surfaces_;
  std::vector<uint32_t> tables_;
  std::vector<PreparedLighting> pixel_lights_;
  host::CaptureDisplay<PF> display_;
  host::DepthCapture depth_capture_;
  std::unique_ptr<Renderer<PF, K>> renderer_;
  Status configured_ = Status::kInvalidArgument;
};

// Colour that encodes a triangle index (id + 1; black = background) exactly through Q1.15.
inline Color15 id_color(uint32_t id) {
  uint32_t v = id + 1;
  return from_rgb8(Rgb8{static_cast<uint8_t>(v & 0xFF), static_cast<uint8_t>((v >> 8) & 0xFF),
                        static_cast<uint8_t>((v >> 16) & 0xFF)});
}
inline int32_t id_of(const host::ImageRgb8& img, size_t pixel) {
  uint32_t v = uint32_t{img.rgb[3 * pixel]} | (uint32_t{img.rgb[3 * pixel + 1]} << 8) |
               (uint32_t{img.rgb[3 * pixel + 2]} << 16);
  return static_cast<int32_t>(v) - 1;
}

// Screen triangles in subpixels, each rendered as its own three vertices with its id colour.
struct ScreenScene {
  std::vector<ScreenVertex> vertices;
  std::vector<std::array<uint16_t, 3>> triangles;
  std::vector<ref::ScreenTri> ref;

  void add(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2, int64_t y2) {
    auto id = static_cast<uint32_t>(triangles.size());
    auto base = static_cast<uint16_t>(vertices.size());
    int64_t xs[3] = {x0, x1, x2}, ys[3] = {y0, y1, y2};
    for (int k = 0; k < 3; ++k) {
      ScreenVertex v;
      v.x = static_cast<int32_t>(xs[k]);
      v.y = static_cast<int32_t>(ys[k]);
      v.z = kDepthMax / 2;
      v.color = id_color(id);
      vertices.push_back(v);
    }
    triangles.push_back({base, static_cast<uint16_t>(base + 1), static_cast<uint16_t>(base + 2)});
    ref.push_back(ref::ScreenTri{{x0, x1, x2}, {y0, y1, y2}});
  }
};

// Draw state for coverage tests: one flat colour per triangle, no depth, nothing culled.
inline DrawState coverage_state() {
  DrawState s;
  s.shading = Shading::kFlat;
  s.lighting = false;
  s.depth_test = false;
  return s;
}

}  // namespace lr::test
