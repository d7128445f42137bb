// The vertex store of a frame: the projected vertices (ScreenVertex) of every draw, in draw order,
// and for the draws that need them their surfaces (Phong) and texture entries, indexed alike;
// and the vertex cache, through which a mesh larger than the free store is binned
// (docs/bands.md). The vertex stage (vertex_stage.hpp) writes a draw's entries; the front end's
// triangle loop (core/binning/front_end.hpp) reads them and refers to them by index from the
// binned triangles.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/vertex/clip.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "lineraster/core/vertex/surface_vertex.hpp"
#include "lineraster/core/vertex/vertex_stage.hpp"

namespace lr {

class VertexStore {
 public:
  // The cache: kCacheSets sets of two slots by mesh index, and a spare per corner for a triangle
  // with three corners in one set.
  static constexpr size_t kCacheSets = 32;
  static constexpr size_t kCacheSlots = 2 * kCacheSets + 3;
  // Smallest store a mesh larger than it can be drawn through: the cache, a clipped polygon and
  // a triangle's copies.
  static constexpr size_t kMinCachedStore = kCacheSlots + kMaxClipVertices + 3;

  // The stores (each at most kMaxEntries entries used: indices are uint16).
  void configure(std::span<ScreenVertex> vertices, std::span<SurfaceVertex> surfaces,
                 std::span<TexVertex> tex, size_t max_entries);
  // Empties the store (a frame, a band).
  void clear() {
    count_ = 0;
    limit_ = vertices_.size();
    cache_first_ = 0;
  }

  size_t count() const { return count_; }
  size_t capacity() const { return vertices_.size(); }
  size_t tex_capacity() const { return tex_.size(); }
  bool has_surfaces() const { return !surfaces_.empty(); }
  bool has_tex() const { return !tex_.empty(); }
  // Whether n more vertices (surfaces, texture entries) fit below the cache.
  bool vertices_fit(size_t n) const { return n <= limit_ - count_; }
  bool surfaces_fit(size_t n) const {
    return surfaces_.size() >= count_ && n <= surfaces_.size() - count_;
  }
  bool tex_fit(size_t n) const { return tex_.size() >= count_ && n <= tex_.size() - count_; }
  // Whether a mesh of n vertices fits whole (else it goes through the cache); whether it can be
  // drawn at all (a store larger than it, or not below the cache's minimum).
  bool mesh_fits(size_t n, bool surfaces, bool tex) const {
    return vertices_fit(n) && (!surfaces || surfaces_fit(n)) && (!tex || tex_fit(n));
  }
  // (cache: false for a renderer without the vertex cache, core/raster/renderer_features.hpp.)
  bool takes_mesh(size_t n, bool surfaces, bool tex, bool cache = true) const {
    auto ok = [n, cache](size_t size) { return n <= size || (cache && size >= kMinCachedStore); };
    return ok(vertices_.size()) && (!surfaces || ok(surfaces_.size())) && (!tex || ok(tex_.size()));
  }

  // Takes the next n entries (their fit checked): returns the first one's index.
  size_t take(size_t n) {
    const size_t first = count_;
    count_ += n;
    return first;
  }
  // Gives back the entries from `count` on (a compaction's end).
  void truncate(size_t count) { count_ = count; }

  ScreenVertex& vertex(size_t i) { return vertices_[i]; }
  const ScreenVertex& vertex(size_t i) const { return vertices_[i]; }
  SurfaceVertex& surface(size_t i) { return surfaces_[i]; }
  TexVertex& tex(size_t i) { return tex_[i]; }
  const TexVertex& tex(size_t i) const { return tex_[i]; }
  ScreenVertex* vertices_at(size_t i) { return vertices_.data() + i; }
  SurfaceVertex* surfaces_at(size_t i) { return surfaces_.data() + i; }
  TexVertex* tex_at(size_t i) { return tex_.data() + i; }

  // What the strip loop reads: the vertices taken, the surfaces and texture entries (indexed
  // alike; as long as given).
  std::span<const ScreenVertex> vertices() const { return vertices_.first(count_); }
  std::span<const SurfaceVertex> surfaces() const { return surfaces_; }
  std::span<const TexVertex> tex_entries() const { return tex_; }

  // The vertex cache (docs/bands.md) while a mesh larger than the free store is binned: it takes
  // the top kCacheSlots entries of the vertex store (and of the surfaces, the texture entries,
  // when the draw has them); the store below ends there. begin_cache: false when that store
  // would be below the minimum (the mesh cannot be drawn).
  bool begin_cache(bool surfaces, bool tex);
  void end_cache() {
    cache_first_ = 0;
    limit_ = vertices_.size();
  }
  // A triangle's corners through the cache: their slots' store indices. Two ways per set of
  // mesh indices (index modulo the sets): a vertex and the one a grid row below it share a set
  // and both stay. A miss replaces the way used least recently, unless an earlier corner of this
  // triangle holds it; a third corner in one set takes its spare. A miss is transformed into its
  // slot by the stage (transformed, wide: the counts of FrameStats).
  std::array<uint16_t, 3> cache_corners(const VertexStage& stage, const Mesh& mesh,
                                        const VertexColors& colors,
                                        const std::array<uint16_t, 3>& tri, uint32_t& transformed,
                                        uint32_t& wide);
  // A cache slot's vertex (and surface, texture entry) copied into the store below the cache,
  // once per slot fill: index becomes the copy's. False when the store is full. An index below
  // the cache (clipped or back-face copies) is kept.
  bool persist(uint16_t& index);

  // Binning a band: keeps only the vertices from `first` on that the draw's triangles refer to
  // (with their surfaces and texture entries when the draw has them), renumbering the
  // triangles' references. for_each_reference(f) calls f(uint16_t& index) for every reference.
  template <class ForEachReference>
  void compact(size_t first, bool surfaces, bool tex, ForEachReference&& for_each_reference);

 private:
  // A kept vertex's mark during compact() (ScreenVertex::color_pending), and the link of one no
  // triangle refers to.
  static constexpr uint8_t kKeptVertex = 2;
  static constexpr uint16_t kNoLink = 0xFFFF;
  // A cache entry: the mesh index (low half) and the store index of its copy (high half;
  // kNoCacheEntry: none yet).
  static constexpr uint32_t kNoCacheEntry = 0xFFFF;

  std::span<ScreenVertex> vertices_{};
  std::span<SurfaceVertex> surfaces_{};
  std::span<TexVertex> tex_{};
  size_t count_ = 0;
  size_t limit_ = 0;  // the store's end below the cache (the store's size without it)
  // The cache (while a cached mesh is binned): its first slot's store index, its entries, per set
  // the way to replace next, and which of the entries it holds.
  size_t cache_first_ = 0;
  std::array<uint32_t, kCacheSlots> cache_{};
  uint32_t cache_lru_ = 0;
  bool cache_surfaces_ = false, cache_tex_ = false;
};

template <class ForEachReference>
void VertexStore::compact(size_t first, bool surfaces, bool tex,
                          ForEachReference&& for_each_reference) {
  for_each_reference([this](uint16_t& v) { vertices_[v].color_pending = kKeptVertex; });
  // The kept vertices' new indices replace their outcode and pending flag (link_of).
  auto kept = static_cast<uint16_t>(first);
  for (size_t i = first; i < count_; ++i)
    set_link(vertices_[i], vertices_[i].color_pending == kKeptVertex ? kept++ : kNoLink);
  for_each_reference([this](uint16_t& v) { v = link_of(vertices_[v]); });
  size_t out = first;
  for (size_t i = first; i < count_; ++i) {
    if (link_of(vertices_[i]) == kNoLink) continue;
    vertices_[out] = vertices_[i];
    vertices_[out].outcode = 0;
    vertices_[out].color_pending = 0;
    if (surfaces) surfaces_[out] = surfaces_[i];
    if (tex) tex_[out] = tex_[i];
    ++out;
  }
  count_ = out;
}

}  // namespace lr
