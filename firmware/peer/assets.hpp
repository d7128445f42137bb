// The peer scenes' meshes and texture: the flash arrays firmware/peer/assets.cmake generates.
#pragma once

#include <span>

#include "firmware/peer/scenes.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "peer_bunny_asset.hpp"   // lineraster-asset --obj bunny.obj --fit-box --fine-positions
#include "peer_bunnyx_asset.hpp"  // ... --fit-box --subdivide 2 --fine-positions
#include "peer_cube_asset.hpp"    // lineraster-asset --obj cube.obj --texture baboon.png
#include "peer_ground_asset.hpp"  // lineraster-asset --obj ground.obj

namespace lr::fw::peer {

inline std::span<const Mesh> meshes(Geometry g) {
  switch (g) {
    case Geometry::kBunny:
      return peer_bunny_asset::meshes;
    case Geometry::kBunnyX:
      return peer_bunnyx_asset::meshes;
    case Geometry::kCube:
      return peer_cube_asset::meshes;
    case Geometry::kGround:
      return peer_ground_asset::meshes;
  }
  return {};
}

// The baboon (RGB565, level 0 only) for the textured scenes, none for the bunny.
inline const Texture* texture(Geometry g) {
  return g == Geometry::kCube || g == Geometry::kGround ? &peer_cube_asset::texture : nullptr;
}

}  // namespace lr::fw::peer
