#include "lineraster/core/vertex/vertex_store.hpp"

namespace lr {

void VertexStore::configure(std::span<ScreenVertex> vertices, std::span<SurfaceVertex> surfaces,
                            std::span<TexVertex> tex, size_t max_entries) {
  vertices_ = vertices.size() > max_entries ? vertices.first(max_entries) : vertices;
  surfaces_ = surfaces;
  tex_ = tex.size() > max_entries ? tex.first(max_entries) : tex;
  clear();
}

bool VertexStore::begin_cache(bool surfaces, bool tex) {
  size_t top = vertices_.size();
  if (surfaces && surfaces_.size() < top) top = surfaces_.size();
  if (tex && tex_.size() < top) top = tex_.size();
  if (top < count_ + kMinCachedStore) return false;
  cache_first_ = top - kCacheSlots;
  limit_ = cache_first_;
  cache_surfaces_ = surfaces;
  cache_tex_ = tex;
  cache_.fill(kNoCacheEntry);
  cache_lru_ = 0;
  return true;
}

std::array<uint16_t, 3> VertexStore::cache_corners(const VertexStage& stage, const Mesh& mesh,
                                                   const VertexColors& colors,
                                                   const std::array<uint16_t, 3>& tri,
                                                   uint32_t& transformed, uint32_t& wide) {
  std::array<uint16_t, 3> vi{};
  for (size_t k = 0; k < 3; ++k) {
    const uint16_t i = tri[k];
    const size_t set = i & (kCacheSets - 1);
    size_t slot = 2 * set;
    if ((cache_[slot] & 0xFFFF) != i) ++slot;
    if ((cache_[slot] & 0xFFFF) != i) {
      const auto taken = [&](size_t s) {
        for (size_t j = 0; j < k; ++j)
          if (vi[j] == cache_first_ + s) return true;
        return false;
      };
      slot = 2 * set + ((cache_lru_ >> set) & 1);
      if (taken(slot)) slot ^= 1;
      if (taken(slot)) slot = 2 * kCacheSets + k;
      const size_t at = cache_first_ + slot;
      wide += stage
                  .transform_range(mesh, colors, i, 1, &vertices_[at],
                                   cache_surfaces_ ? &surfaces_[at] : nullptr,
                                   cache_tex_ ? &tex_[at] : nullptr)
                  .wide;
      cache_[slot] = i | kNoCacheEntry << 16;
      ++transformed;
    }
    // The other way of the set is replaced next.
    if (slot < 2 * kCacheSets)
      cache_lru_ = (cache_lru_ & ~(uint32_t{1} << set)) | uint32_t((slot & 1) ^ 1) << set;
    vi[k] = static_cast<uint16_t>(cache_first_ + slot);
  }
  return vi;
}

bool VertexStore::persist(uint16_t& index) {
  if (index < cache_first_) return true;  // already in the store (clipping, back faces)
  uint32_t& e = cache_[index - cache_first_];
  auto p = static_cast<uint16_t>(e >> 16);
  if (p == kNoCacheEntry) {
    if (count_ >= limit_) return false;
    p = static_cast<uint16_t>(count_++);
    vertices_[p] = vertices_[index];
    if (cache_surfaces_) surfaces_[p] = surfaces_[index];
    if (cache_tex_) tex_[p] = tex_[index];
    e = (e & 0xFFFF) | uint32_t{p} << 16;
  }
  index = p;
  return true;
}

}  // namespace lr
