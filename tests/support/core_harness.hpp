// Test harness: a Renderer with host-allocated storage and a capture display, plus helpers to
// give each triangle its own identifying colour so coverage can be read back per pixel.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "tests/reference/ref_renderer.hpp"

namespace lr::test {

template <int K = 8, class PF = Rgb888, SpanSet kSet = kAllSpans>
class CoreHarness {
 public:
  // tex_vertices: the TexVertex store (kAsVertices: as large as the vertex store).
  static constexpr size_t kAsVertices = SIZE_MAX;
  CoreHarness(int width, int height, size_t max_vertices = 0xFFFF, size_t max_triangles = 0xFFFE,
              size_t max_active = 1024, size_t max_draws = 64, size_t tex_vertices = kAsVertices)
      : width_(width),
        height_(height),
        store_(capacities(width, height, max_vertices, max_triangles, max_active, max_draws,
                          tex_vertices)),
        display_(static_cast<size_t>(width) * K),
        renderer_(std::make_unique<Renderer<PF, K, kSet>>()) {
    configured_ = renderer_->configure(store_.storage(), width, height);
  }
  Status configured() const { return configured_; }
  Renderer<PF, K, kSet>& renderer() { return *renderer_; }
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
  // Every store, with room for Phong draws: a surface per vertex, 16 materials, 4 tables.
  static FrameCapacities capacities(int width, int height, size_t vertices, size_t triangles,
                                    size_t active, size_t draws, size_t tex_vertices) {
    FrameCapacities c;
    c.width = width;
    c.height = height;
    c.strip_height = K;
    c.vertices = vertices;
    c.triangles = triangles;
    c.draws = draws;
    c.active = active;
    c.surfaces = vertices;
    c.tex_vertices = tex_vertices == kAsVertices ? vertices : tex_vertices;
    c.active_extra = active;
    c.triangle_colors = triangles;
    c.lighting_table_words = 4 * lighting_table_words(kMaxLightingTable, true);
    c.pixel_lights = 16;
    return c;
  }

  BasicFrameStorage<std::vector> store_;
  host::CaptureDisplay<PF> display_;
  host::DepthCapture depth_capture_;
  std::unique_ptr<Renderer<PF, K, kSet>> renderer_;
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
