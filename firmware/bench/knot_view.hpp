// The torus knot's view and knot64k_gouraud's draw state, shared by the benchmark cases
// (firmware/bench/cases.hpp) and the small-RAM program (firmware/peer/small_ram.cpp), which
// draws the same frame in 64 KB: lineraster-sim's default view from (0, 0, 2.4), lit Gouraud
// in "gold", back faces culled.
#pragma once

#include "firmware/demo/scene.hpp"
#include "lineraster/core/scene/draw_state.hpp"

namespace lr::fw::bench {

inline constexpr demo::SceneView kKnotView{demo::kSimDefaultView.fovy,   demo::kSimDefaultView.near,
                                           demo::kSimDefaultView.far,    demo::vec(0, 0, 2.4),
                                           demo::kSimDefaultView.target, demo::kSimDefaultView.up};

consteval DrawState knot64k_state() {
  DrawState s;
  s.shading = Shading::kGouraud;
  s.lighting = true;
  s.cull = Cull::kBack;
  return s;
}

}  // namespace lr::fw::bench
