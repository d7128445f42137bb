// The texel fetch interface: what a span routine calls to read a batch of texels. The fetch
// routines themselves (format x filter x wrap) are in core/span/sampler.hpp; draw records hold a
// pointer to the one their texture needs, so this signature lives with the texture.
#pragma once

#include <cstdint>

#include "lineraster/core/texture/texture.hpp"

namespace lr {

using Texel = uint32_t;  // 0x00RRGGBB

// Fetches n texels of level `level` at coordinates (s[i], t[i]) (level-0 texels in Q.8).
using FetchFn = void (*)(const Texture& tex, int level, const int32_t* s, const int32_t* t, int n,
                         Texel* out);

}  // namespace lr
