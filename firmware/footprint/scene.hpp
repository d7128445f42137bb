// The footprint images' scene, computed at compile time into flash: a torus of 1,000 triangles
// (25 segments around the axis x 20 around the tube, 546 vertices: the seams are duplicated so
// that texture coordinates wrap) with smooth normals, vertex colours and texture coordinates, and
// a 32 x 32 RGB565 texture. Floating point appears only in consteval code: nothing of it reaches
// a target (the M0+ has no FPU and links no soft-float routines for it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr::fw::footprint {

inline constexpr int kRing = 25;  // segments around the torus's axis (y)
inline constexpr int kTube = 20;  // segments around the tube
inline constexpr size_t kVertexCount = size_t{kRing + 1} * (kTube + 1);
inline constexpr size_t kTriangleCount = size_t{2} * kRing * kTube;
static_assert(kTriangleCount == 1000);

namespace detail {

inline constexpr double kPi = 3.14159265358979323846;

// sin by its Taylor series after reduction to [-pi, pi]: 1e-15 there, ample for Q16.16 and Q1.14.
consteval double sine(double x) {
  while (x > kPi) x -= 2 * kPi;
  while (x < -kPi) x += 2 * kPi;
  double term = x, sum = x;
  for (int n = 1; n < 14; ++n) {
    term *= -x * x / ((2.0 * n) * (2.0 * n + 1));
    sum += term;
  }
  return sum;
}
consteval double cosine(double x) {
  return sine(x + kPi / 2);
}

consteval int16_t q14(double v) {
  return static_cast<int16_t>(v * 16384 + (v >= 0 ? 0.5 : -0.5));
}

// Vertex (i, j): i around the axis, j around the tube; both run to their count inclusive.
constexpr size_t vertex(int i, int j) {
  return static_cast<size_t>(i * (kTube + 1) + j);
}
constexpr double kMajorRadius = 1.0, kMinorRadius = 0.42;

struct Frame {
  double px, py, pz;  // position
  double nx, ny, nz;  // unit normal
};
consteval Frame frame(int i, int j) {
  const double a = 2 * kPi * i / kRing, b = 2 * kPi * j / kTube;
  const double ca = cosine(a), sa = sine(a), cb = cosine(b), sb = sine(b);
  const double d = kMajorRadius + kMinorRadius * cb;
  return {d * ca, kMinorRadius * sb, d * sa, cb * ca, sb, cb * sa};
}

consteval std::array<Vec3, kVertexCount> make_positions() {
  std::array<Vec3, kVertexCount> out{};
  for (int i = 0; i <= kRing; ++i)
    for (int j = 0; j <= kTube; ++j) {
      const Frame f = frame(i, j);
      out[vertex(i, j)] = {Fixed::from_double(f.px), Fixed::from_double(f.py),
                           Fixed::from_double(f.pz)};
    }
  return out;
}

consteval std::array<Normal16, kVertexCount> make_normals() {
  std::array<Normal16, kVertexCount> out{};
  for (int i = 0; i <= kRing; ++i)
    for (int j = 0; j <= kTube; ++j) {
      const Frame f = frame(i, j);
      out[vertex(i, j)] = {q14(f.nx), q14(f.ny), q14(f.nz)};
    }
  return out;
}

// Unlit colours: red around the axis, green around the tube.
consteval std::array<Rgb8, kVertexCount> make_colors() {
  std::array<Rgb8, kVertexCount> out{};
  for (int i = 0; i <= kRing; ++i)
    for (int j = 0; j <= kTube; ++j)
      out[vertex(i, j)] = {static_cast<uint8_t>(64 + 191 * i / kRing),
                           static_cast<uint8_t>(64 + 191 * j / kTube), 96};
  return out;
}

// The texture repeats 4 times around the axis and twice around the tube (Q12.20).
consteval std::array<TexCoord, kVertexCount> make_uvs() {
  std::array<TexCoord, kVertexCount> out{};
  for (int i = 0; i <= kRing; ++i)
    for (int j = 0; j <= kTube; ++j)
      out[vertex(i, j)] = {(4 << TexCoord::kFracBits) / kRing * i,
                           (2 << TexCoord::kFracBits) / kTube * j};
  return out;
}

// Two triangles per quad, counter-clockwise seen from outside (checked below).
consteval std::array<std::array<uint16_t, 3>, kTriangleCount> make_triangles() {
  std::array<std::array<uint16_t, 3>, kTriangleCount> out{};
  size_t n = 0;
  for (int i = 0; i < kRing; ++i)
    for (int j = 0; j < kTube; ++j) {
      const auto a = static_cast<uint16_t>(vertex(i, j)),
                 b = static_cast<uint16_t>(vertex(i + 1, j)),
                 c = static_cast<uint16_t>(vertex(i + 1, j + 1)),
                 d = static_cast<uint16_t>(vertex(i, j + 1));
      out[n++] = {a, d, c};
      out[n++] = {a, c, b};
    }
  return out;
}

// Every face's normal (counter-clockwise winding) points the way its vertices' normals do.
consteval bool outward_winding() {
  const auto tris = make_triangles();
  for (const auto& t : tris) {
    Frame f[3];
    for (int k = 0; k < 3; ++k) {
      const int i = t[static_cast<size_t>(k)] / (kTube + 1),
                j = t[static_cast<size_t>(k)] % (kTube + 1);
      f[k] = frame(i, j);
    }
    const double ux = f[1].px - f[0].px, uy = f[1].py - f[0].py, uz = f[1].pz - f[0].pz;
    const double vx = f[2].px - f[0].px, vy = f[2].py - f[0].py, vz = f[2].pz - f[0].pz;
    const double cx = uy * vz - uz * vy, cy = uz * vx - ux * vz, cz = ux * vy - uy * vx;
    if (cx * f[0].nx + cy * f[0].ny + cz * f[0].nz <= 0) return false;
  }
  return true;
}
static_assert(outward_winding(), "torus triangles must be counter-clockwise from outside");

// A 32 x 32 RGB565 texture: an 8 x 8 checkerboard of two tints with a darker border per tile.
consteval std::array<uint16_t, 32 * 32> make_texels() {
  std::array<uint16_t, 32 * 32> out{};
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const bool odd = ((x / 4) ^ (y / 4)) & 1;
      const bool edge = x % 4 == 0 || y % 4 == 0;
      const unsigned r = odd ? 28 : 6, g = odd ? 50 : 40, b = odd ? 8 : 26;
      const unsigned s = edge ? 2 : 1;
      out[static_cast<size_t>(y * 32 + x)] =
          static_cast<uint16_t>(((r / s) << 11) | ((g / s) << 5) | (b / s));
    }
  return out;
}

}  // namespace detail

// Each array is its own constant: an image links only those its draw references.
inline constexpr std::array<Vec3, kVertexCount> kPositions = detail::make_positions();
inline constexpr std::array<Normal16, kVertexCount> kNormals = detail::make_normals();
inline constexpr std::array<Rgb8, kVertexCount> kColors = detail::make_colors();
inline constexpr std::array<TexCoord, kVertexCount> kUvs = detail::make_uvs();
inline constexpr std::array<std::array<uint16_t, 3>, kTriangleCount> kTriangles =
    detail::make_triangles();
inline constexpr std::array<uint16_t, 32 * 32> kTexels = detail::make_texels();

constexpr Texture make_texture() {
  Texture t{};
  t.format = TexelFormat::kRgb565;
  t.levels[0].rgb565 = kTexels;
  t.levels[0].width = 32;
  t.levels[0].height = 32;
  t.level_count = 1;
  return t;
}
inline constexpr Texture kTexture = make_texture();

}  // namespace lr::fw::footprint
