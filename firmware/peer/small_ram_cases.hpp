// The cases of the small-RAM program (small_ram.cpp): a scene, its RAM budget and the
// stores that fit it. The stores hold a fraction of the mesh, sized for the frame's fullest
// rows; smaller ones still draw the frame, in more bands and passes, down to the minimum of
// docs/bands.md. The stack is set per image (firmware/peer/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>

namespace lr::fw::peer::small {

// The scene of lr_bench's knot64k_gouraud (firmware/bench/cases.hpp), not a peer scene.
inline constexpr size_t kKnotScene = ~size_t{0};

struct SmallRamCase {
  const char* name;       // the image, and its messages' prefix
  const char* case_name;  // its lr_bench case line
  const char* ppm;        // the frame's file, in QEMU's working directory
  size_t scene;           // index into kScenes (scenes.hpp), or kKnotScene
  uint32_t ram_budget;    // bytes of .data + .bss + stack
  int strip_rows;
  size_t vertices;        // the vertex cache's 67 entries and the copies of one band
  size_t triangles;       // binned triangles of one band
  size_t active;          // triangles rasterized at once (more: the strip in passes)
  bool one_pass = false;  // the stores hold the whole frame: one band, no strip in passes
};

// S1, the bunny (1,839 vertices, 3,674 triangles), in the micro:bit's 16 KB: strips of one row
// (two colour strips and a depth strip of 640 B each) and a 3 KB stack.
inline constexpr SmallRamCase kBunny16k{
    "lr_peer_bunny_16k", "S1-16k", "lr_peer_bunny_16k.ppm", 0, 16 * 1024, 1, 216, 128, 4};

// S1 in 64 KB in one pass (one band, no strip in passes): strips of two rows (1,280 B each),
// stores for the frame's 1,377 binned triangles (1,380), the vertices they use through the
// vertex cache (1,200; 1,100 takes a second band) and its fullest strip's 79 active triangles
// (80), and a 3 KB stack.
inline constexpr SmallRamCase kBunny64k{
    "lr_peer_bunny_64k", "S1-64k", "lr_peer_bunny_64k.ppm", 0, 64 * 1024, 2, 1200, 1380, 80, true};

// S1x, the bunny subdivided twice (29,394 vertices, 58,784 triangles; about 2.5 MB in one
// pass), in 64 KB: strips of two rows (1,280 B each) and a 4 KB stack.
inline constexpr SmallRamCase kBunnyx64k{
    "lr_peer_bunnyx_64k", "S1x-64k", "lr_peer_bunnyx_64k.ppm", 1, 64 * 1024, 2, 1536, 1536, 16};

// knot64k_gouraud, the torus knot subdivided twice (32,841 vertices, 64,000 triangles; 1.3 MB
// in one pass, 108 KB in lr_bench's small stores), in 64 KB: S1x's strips, stores and stack.
inline constexpr SmallRamCase kKnot64k64k{"lr_peer_knot64k_64k",
                                          "knot64k_gouraud-64k",
                                          "lr_peer_knot64k_64k.ppm",
                                          kKnotScene,
                                          64 * 1024,
                                          2,
                                          1536,
                                          1536,
                                          16};

}  // namespace lr::fw::peer::small
