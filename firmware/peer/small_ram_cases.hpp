// The cases of the small-RAM program (small_ram.cpp): a peer scene, its RAM budget and the
// stores that fit it. The stores hold a fraction of the mesh, sized for the frame's fullest
// rows; smaller ones still draw the frame, in more bands and passes, down to the minimum of
// docs/bands.md. The stack is set per image (firmware/peer/CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>

namespace lr::fw::peer::small {

struct SmallRamCase {
  const char* name;       // the image, and its messages' prefix
  const char* case_name;  // its lr_bench case line
  const char* ppm;        // the frame's file, in QEMU's working directory
  size_t scene;           // index into kScenes (scenes.hpp)
  uint32_t ram_budget;    // bytes of .data + .bss + stack
  int strip_rows;
  size_t vertices;   // the vertex cache's 67 entries and the copies of one band
  size_t triangles;  // binned triangles of one band
  size_t active;     // triangles rasterized at once (more: the strip in passes)
};

// S1, the bunny (1,839 vertices, 3,674 triangles), in the micro:bit's 16 KB: strips of one row
// (two colour strips and a depth strip of 640 B each) and a 3 KB stack.
inline constexpr SmallRamCase kBunny16k{
    "lr_peer_bunny_16k", "S1-16k", "lr_peer_bunny_16k.ppm", 0, 16 * 1024, 1, 216, 128, 4};

// S1x, the bunny subdivided twice (29,394 vertices, 58,784 triangles; about 2.5 MB in one
// pass), in 64 KB: strips of two rows (1,280 B each) and a 4 KB stack.
inline constexpr SmallRamCase kBunnyx64k{
    "lr_peer_bunnyx_64k", "S1x-64k", "lr_peer_bunnyx_64k.ppm", 1, 64 * 1024, 2, 1536, 1536, 16};

}  // namespace lr::fw::peer::small
