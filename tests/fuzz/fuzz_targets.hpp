// The fuzz targets, shared by the libFuzzer executables (clang, tests/fuzz/CMakeLists.txt as its
// own project, run by scripts/fuzz.sh) and the regression test of the main build (g++), which
// replays every committed seed and crash input (tests/fuzz/corpus/<target>/ and
// tests/fuzz/regressions/<target>/).
//
// Each target takes arbitrary bytes, must never crash or trip a sanitizer, and checks cheap
// invariants of what it ran: a broken invariant prints one line and aborts (a crash to libFuzzer,
// a failed test to CTest).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace lr::fuzz {

// Wavefront OBJ + MTL: the input is an OBJ, optionally followed by the line "#mtl" and the text of
// an MTL that the OBJ can name as `mtllib m.mtl` (kept in a private temporary folder); the MTL
// part is also given to parse_mtl directly. A successful load is checked for consistency and
// written back as OBJ text, which must load again to the same mesh.
int obj_target(const uint8_t* data, size_t size);

// Images: the input as an image file (in memory, through memfd) for read_png / read_image and
// load_texture in every texel format, with and without mipmaps.
int png_target(const uint8_t* data, size_t size);

// The pipeline: a header (viewport, strip height, pixel format, draw state, texture, camera,
// capacities) followed by vertices and triangles for Renderer::draw and draw_screen,
// rendered into a CaptureDisplay; checks the frame statistics add up. Layout in
// pipeline_target.cpp.
int pipeline_target(const uint8_t* data, size_t size);

[[noreturn]] inline void check_failed(const char* file, int line, const char* what) {
  std::fprintf(stderr, "%s:%d: fuzz invariant failed: %s\n", file, line, what);
  std::fflush(stderr);
  std::abort();
}

}  // namespace lr::fuzz

#define LR_FUZZ_CHECK(cond)                                           \
  do {                                                                \
    if (!(cond)) ::lr::fuzz::check_failed(__FILE__, __LINE__, #cond); \
  } while (0)
