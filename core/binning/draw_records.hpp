// The frame's draw records (draw_record.hpp): one per draw, from its state, in draw order; the
// per-pixel lighting of Phong draws, shared between draws of equal materials (prepared lighting,
// lighting tables); each record's signature for skipping unchanged strips.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/material.hpp"

namespace lr {

class DrawRecords {
 public:
  // The stores: the records (at most 256: their index is a uint8), the lighting tables' words
  // and the prepared lighting of Phong draws (both may be empty).
  void configure(std::span<DrawRecord> draws, std::span<uint32_t> lighting_tables,
                 std::span<PreparedLighting> pixel_lights) {
    draws_ = draws;
    lighting_tables_ = lighting_tables;
    pixel_lights_ = pixel_lights;
    begin_frame(nullptr, false);
  }
  // Empties the records; view: the frame's view matrix (environment maps read it), two_sided:
  // the lights' two-sided model (Phong records carry it).
  void begin_frame(const Mat4* view, bool two_sided) {
    count_ = pixel_light_count_ = table_words_used_ = 0;
    view_ = view;
    two_sided_ = two_sided;
  }

  size_t count() const { return count_; }
  bool full() const { return count_ >= draws_.size(); }
  DrawRecord& operator[](size_t i) { return draws_[i]; }
  const DrawRecord& operator[](size_t i) const { return draws_[i]; }
  std::span<DrawRecord> records() const { return draws_.first(count_); }
  bool has_pixel_lights() const { return !pixel_lights_.empty(); }
  bool has_lighting_tables() const { return !lighting_tables_.empty(); }

  // A new record for a draw's state (not full()): returns its index. first_vertex: where its
  // vertices will start in the vertex store (set again when it is binned).
  // A textured state's fields are not set here: texture_fields() sets them (FrontEndRoutines::
  // maps: a renderer without textured spans links none of them).
  uint8_t add(const DrawState& state, bool color_planes, uint16_t first_vertex);
  // A record's texture, sampler and perspective fields from a textured state.
  static void texture_fields(DrawRecord& r, const DrawState& state);
  // Takes back the last record (a draw refused after it was added).
  void drop_last() { --count_; }
  // The record's signature, once it is final (per_pixel_material: a Phong draw's material).
  void sign(uint8_t index, const Material* per_pixel_material);

  // The per-pixel lighting part of a Phong draw's record r: its prepared lighting pl, shared
  // with the draws of an equal material, and for the table method its lighting table, shared
  // likewise. kCapacity when a pool is full. What a renderer with Phong spans passes as the
  // front end's PhongRecordFn (phong_record).
  Status add_phong_state(const DrawState& state, const PreparedLighting& pl, DrawRecord& r);
  static Status phong_record(DrawRecords& records, const DrawState& state,
                             const PreparedLighting& pl, DrawRecord& r) {
    return records.add_phong_state(state, pl, r);
  }

 private:
  std::span<DrawRecord> draws_{};
  std::span<uint32_t> lighting_tables_{};
  std::span<PreparedLighting> pixel_lights_{};
  size_t count_ = 0, pixel_light_count_ = 0, table_words_used_ = 0;
  const Mat4* view_ = nullptr;
  bool two_sided_ = false;
};

}  // namespace lr
