// Double-precision reference renderer (tests and benchmarks only, never firmware).
//
// Follows the conventions of docs/conventions.md (those of OpenGL) but evaluates everything
// directly per pixel: exact integer edge functions on the snapped vertices for coverage, and
// perspective-correct barycentrics for the attributes. No incremental stepping, no fixed point.
//
// Pipeline per mesh triangle, in submission order:
//   clip = P * V * M * pos; lighting (or vertex colours) at the original vertices;
//   Sutherland-Hodgman against the near (z >= -w) and far (z <= w) planes in clip space,
//   interpolating clip coordinates and colours linearly; fan the polygon (0, k, k + 1);
//   window x = (x/w + 1) * W / 2, y = (1 - y/w) * H / 2, depth = (z/w + 1) / 2;
//   x, y snapped to 1/2^bits pixel with std::llround; zero-area pieces dropped;
//   back faces (signed display area > 0) dropped when cull_back;
//   fill rule: centre inside, or exactly on a left or bottom edge (display coordinates, y down);
//   depth interpolated linearly in screen space, test LESS, then written;
//   with a texture: (u, v) interpolated perspective-correctly, level of detail from the exact
//   analytic screen-space derivatives of (u, v) at the pixel centre, sampled per GL (section 8.14
//   of the 4.x spec: GL_NEAREST / GL_LINEAR, GL_*_MIPMAP_NEAREST / _LINEAR, GL_REPEAT /
//   GL_CLAMP_TO_EDGE), combined per docs/conventions.md#textures (GL_MODULATE with
//   GL_SEPARATE_SPECULAR_COLOR, or GL_REPLACE).
// Phong shading carries world normals, world and model positions and tangents through clipping
// like the colours and lights every covered pixel (see RefParams: normal_interp, envmap,
// normal_map); two_sided picks the back-face lighting per screen triangle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lineraster/host_sim/formats/host_mesh.hpp"
#include "tests/reference/ref_math.hpp"

namespace lr::ref {

enum class RefLightKind { Directional, Point };

// A GL fixed-function light (no spot lights).
// Directional: direction is in world space, from the surface towards the light (normalized by
// the renderer). Point: position is the light's world position, L = normalize(position - P), and
// the light's three terms are multiplied by GL's attenuation 1 / (constant + linear d +
// quadratic d^2), d = the world distance from the lit point P to the light (directional lights
// are never attenuated).
// Colours: the light's ambient, diffuse and specular colours all equal color (the project's
// convention), unless separate_colors is set: then ambient, diffuse and specular are used and
// color is ignored.
struct RefLight {
  Vec3d direction{1, 1, 1};  // directional lights
  Vec3d color{1, 1, 1};
  RefLightKind kind = RefLightKind::Directional;
  Vec3d position{0, 0, 0};  // point lights, world space
  double constant = 1, linear = 0, quadratic = 0;
  bool separate_colors = false;
  Vec3d ambient{0, 0, 0};
  Vec3d diffuse{1, 1, 1};
  Vec3d specular{1, 1, 1};
};

struct RefMaterial {
  Vec3d ambient{0.1, 0.1, 0.1};
  Vec3d diffuse{0.8, 0.8, 0.8};
  Vec3d specular{0.5, 0.5, 0.5};
  Vec3d emission{0, 0, 0};
  double shininess = 32;  // GL range [0, 128]
};

// Flat: the face normal, lit once per triangle. Gouraud: lit per vertex, colours interpolated.
// Phong: normals (and world positions) interpolated, lit per pixel; see RefParams.
enum class RefShading { Flat, Gouraud, Phong };

// How Phong shading finds the pixel's normal (before normal mapping and two-sided negation).
//   Linear: the perspective-correct interpolation of the three vertex world normals, normalized.
//   Slerp: the scanline method: the pixel centre row y crosses the (clipped, snapped) screen
//     triangle's left and right edges at xl and xr; the normal at each crossing is the slerp of
//     that edge's two (normalized) vertex normals by the screen-space parameter along the edge,
//     and the pixel's normal the slerp between the left and right normals by (x - xl) / (xr - xl)
//     (x the pixel centre). slerp(a, b, t) = sin((1-t)th)/sin(th) a + sin(t th)/sin(th) b,
//     th = acos(a.b); normalized lerp where th < 1e-9 or sin(th) < 1e-9.
//   SphereAnalytic: normalize(the perspective-correct interpolated MODEL-space position),
//     transformed to world by the model's normal matrix: the exact normal of a sphere centred at
//     the model origin, for measuring the error of the other methods.
enum class RefNormalInterp { Linear, Slerp, SphereAnalytic };

// ---- Textures ----

// One mip level: width x height texels, row-major, row 0 = the BOTTOM row (v near 0: GL's order,
// the image file's last row). Texel (i, j) has its centre at u = (i + 0.5) / width,
// v = (j + 0.5) / height. Colours in [0, 1].
struct RefLevel {
  int width = 0, height = 0;
  std::vector<Vec3d> texels;

  const Vec3d& at(int i, int j) const {
    return texels[static_cast<size_t>(j) * static_cast<size_t>(width) + static_cast<size_t>(i)];
  }
};

// Level 0 and its mip chain (each level GL's floor-halved size of the one before, at least 1).
// The chain may stop early: the last level given is GL's TEXTURE_MAX_LEVEL (q). An empty texture
// or one with an empty level 0 is incomplete: it samples as black, as GL's incomplete textures.
// tests/reference/ref_texture_core.hpp builds one from a core lr::Texture.
struct RefTexture {
  std::vector<RefLevel> levels;
};

enum class RefFilter { Nearest, Bilinear };       // GL_NEAREST, GL_LINEAR
enum class RefWrap { Repeat, ClampToEdge };       // GL_REPEAT, GL_CLAMP_TO_EDGE
enum class RefMipMode { None, Nearest, Linear };  // level 0 only, GL_*_MIPMAP_NEAREST, _LINEAR
enum class RefTexEnv { Modulate, Replace };       // see RefParams::tex_env

struct RefParams {
  int width = 320, height = 240;
  Mat4d model, view, projection;  // identity by default
  std::vector<RefLight> lights;
  Vec3d global_ambient{0, 0, 0};
  RefMaterial material;  // used for every triangle (mesh.triangle_material is not consulted)
  RefShading shading = RefShading::Gouraud;
  // Unlit: vertex colours if the mesh has them, else material.diffuse; flat + unlit takes the
  // LAST vertex's colour (GL's provoking vertex).
  bool unlit = false;
  bool depth_test = true;  // LESS, depth written; when false depth is neither tested nor written
  bool cull_back = false;
  // Blinn half vector with V = normalize(eye - P) instead of the infinite viewer's V = the view's
  // +Z axis in world space (third row of the view matrix's upper 3x3).
  bool local_viewer = false;
  Vec3d background{0, 0, 0};
  int subpixel_bits = 8;  // 1..16; screen x, y snapped to 1/2^bits pixel, round to nearest

  // Texturing (off when null; the texture must outlive render()). Texture coordinates come from
  // mesh.uvs (one per vertex; absent or of the wrong size: every vertex has (0, 0)). Defaults
  // mirror lr::Sampler's. The same filter serves magnification and minification (GL's
  // TEXTURE_MAG_FILTER = the min filter's base), so the switch point is lambda = 0.
  const RefTexture* texture = nullptr;
  RefFilter filter = RefFilter::Bilinear;
  RefWrap wrap_s = RefWrap::Repeat;  // u
  RefWrap wrap_t = RefWrap::Repeat;  // v
  RefMipMode mip = RefMipMode::None;
  // Modulate, lit: clamp(texel * primary + secondary), primary = emission + ambient + diffuse
  // (clamped to [0, 1]), secondary = specular (clamped): GL_MODULATE with
  // GL_SEPARATE_SPECULAR_COLOR. Gouraud interpolates primary and secondary separately
  // (perspective-correct); flat computes them once per face. Unlit: texel * vertex colour (or
  // material.diffuse; flat: the last vertex's colour).
  // Replace: the texel alone, lit or not.
  RefTexEnv tex_env = RefTexEnv::Modulate;

  // GL_LIGHT_MODEL_TWO_SIDE: back faces (signed_area2 > 0 of the snapped screen triangle,
  // clockwise in NDC) are lit with the negated normal: Gouraud lights their vertices with -n,
  // Flat the negated face normal, Phong the negated per-pixel normal. Front faces unchanged.
  bool two_sided = false;

  // ---- Phong shading (shading == Phong) ----
  // Per pixel: N from normal_interp; the world position P is the perspective-correct
  // interpolation of the vertex world positions; clipped vertices interpolate normals, positions
  // and tangents linearly in clip space as colours are. Vertex world normals as Gouraud's
  // (normal matrix, normalized; zero without mesh normals). Untextured: light_point(N, P).
  // With a texture and/or an envmap: clamp(base texel * env texel * primary + secondary) from
  // light_point_separate(N, P) (a missing map counts as 1); Replace: the base texel alone (times
  // the env texel if any). Unlit Phong shades as unlit Gouraud (RefFrame::normal still written);
  // envmap and normal_map apply to lit Phong only.
  RefNormalInterp normal_interp = RefNormalInterp::Linear;
  // Sphere environment map (GL_SPHERE_MAP), must outlive render(). v = the unit vector towards
  // the viewer (infinite viewer: the view's +Z axis in world space; local viewer:
  // normalize(eye - P)); r = 2 (N.v) N - v in world space, taken to eye space by the view's
  // upper 3x3; m = 2 sqrt(rx^2 + ry^2 + (rz + 1)^2); (u, v) = (rx / m + 0.5, ry / m + 0.5), or
  // (0.5, 0.5) where m = 0; sampled with sample_level(level 0, Bilinear, ClampToEdge x 2).
  const RefTexture* envmap = nullptr;
  // Tangent-space normal map (RGB = (n + 1) / 2), must outlive render(). Needs mesh.uvs and
  // mesh.tangents (absent or of the wrong size: every tangent is (0, 0, 0, 1)). Vertex world
  // tangent = normalize(model's upper 3x3 * tangent.xyz). Per pixel: T = the perspective-correct
  // interpolated world tangent, T = normalize(T - (N.T) N), B = w cross(N, T) with w the
  // tangent.w of the mesh triangle's first vertex; c = sample_level(level 0, filter, wrap_s,
  // wrap_t) at the pixel's (u, v); tn = 2c - 1; N' = normalize(tn.x T + tn.y B + tn.z N).
  // Two-sided back faces negate N before the frame is built. Incomplete maps sample black.
  const RefTexture* normal_map = nullptr;
};

struct RefFrame {
  int width = 0, height = 0;
  std::vector<Vec3d> color;    // final colour per pixel, [0, 1] (before byte rounding)
  std::vector<uint8_t> rgb8;   // round(255 * c) per channel, 3 bytes per pixel, row 0 = top
  std::vector<double> depth;   // window depth [0, 1]; 1.0 (cleared) where nothing drawn
  std::vector<int32_t> owner;  // index of the mesh triangle that wrote the pixel last, -1 = none
  // Level of detail lambda = log2(rho) of the textured fragment that wrote the pixel (-infinity
  // where the derivatives vanish); NaN where no textured fragment was written.
  std::vector<double> lod;
  // The final world-space shading normal (after normal mapping and two-sided negation) of the
  // Phong fragment that wrote the pixel last; {0, 0, 0} where no Phong fragment was written.
  std::vector<Vec3d> normal;

  size_t index(int x, int y) const {
    return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
  }
};

// Renders mesh into out (resized to params.width x params.height and cleared first).
void render(const host::HostMesh& mesh, const RefParams& params, RefFrame& out);

// The lit colour (clamped to [0, 1]) of a surface point: OpenGL fixed-function lighting with
// params.material, params.lights, params.global_ambient and params.local_viewer.
// normal_world must be unit length; position_world is used only for point lights and the local
// viewer.
Vec3d light_point(const RefParams& params, const Vec3d& normal_world, const Vec3d& position_world);

// The same lighting split as GL_SEPARATE_SPECULAR_COLOR does: primary = emission + global
// ambient * Ka + sum of (La * Ka + max(N.L, 0) * Ld * Kd), secondary = sum over lights with
// N.L > 0 of max(N.H, 0)^shininess * Ls * Ks; each clamped to [0, 1].
struct RefLitColor {
  Vec3d primary{0, 0, 0};
  Vec3d secondary{0, 0, 0};
};
RefLitColor light_point_separate(const RefParams& params, const Vec3d& normal_world,
                                 const Vec3d& position_world);

// ---- Texture sampling (what render() does per textured fragment) ----

// GL_NEAREST or GL_LINEAR sample of one level at (u, v): s = u * width, t = v * height;
// nearest: texel (floor(s), floor(t)); bilinear: i0 = floor(s - 0.5), alpha = frac(s - 0.5),
// i1 = i0 + 1 (likewise j, beta), each index wrapped (repeat: mod size, non-negative; clamp to
// edge: clamped to [0, size - 1]), blended (1-a)(1-b) T00 + a(1-b) T10 + (1-a)b T01 + ab T11.
// An empty level gives black.
Vec3d sample_level(const RefLevel& level, double u, double v, RefFilter filter, RefWrap wrap_s,
                   RefWrap wrap_t);

// The full GL texture lookup at (u, v) with level of detail lambda (log2 of rho, in level-0
// texels per pixel; -infinity allowed) under params' filter, wraps and mip mode:
//   None: level 0. lambda <= 0 (magnification): level 0 in every mode.
//   Nearest: level ceil(lambda + 0.5) - 1, clamped to [0, q] (q = last level).
//   Linear: lambda clamped to q; d1 = floor(lambda), d2 = min(d1 + 1, q), blended with
//   frac(lambda).
Vec3d sample_texture(const RefTexture& texture, const RefParams& params, double u, double v,
                     double lambda);

// lambda = log2(max(sqrt(ds/dx^2 + dt/dx^2), sqrt(ds/dy^2 + dt/dy^2))) from the derivatives of
// u and v with respect to window x and y (pixels) and level 0's size. -infinity when rho = 0.
double texture_lod(double du_dx, double dv_dx, double du_dy, double dv_dy, int width0, int height0);

// ---- Screen-space coverage ----

// A triangle with vertices already snapped: display coordinates (y down) in subpixel units
// (2^bits per pixel). Either winding.
struct ScreenTri {
  int64_t x[3], y[3];
};

// The exact fill rule: is the point (normally a pixel centre, i * S + S / 2, j * S + S / 2)
// covered? Strictly inside: yes. Exactly on an edge: yes iff the edge is a left edge (interior at
// larger x) or a bottom edge (horizontal, interior at smaller display y) -- for every edge it
// lies on. Zero-area triangles cover nothing. Coordinates must satisfy |v| <= 2^60.
bool covers(const ScreenTri& tri, int64_t px_centre_x_sub, int64_t px_centre_y_sub);

// hits[p] = number of triangles covering pixel p's centre; owner[p] = index of the last covering
// triangle or -1. Both are resized to width * height (row-major, row 0 = top).
void coverage(const std::vector<ScreenTri>& tris, int width, int height, int subpixel_bits,
              std::vector<int32_t>& hits, std::vector<int32_t>& owner);

// Signed display-space area (doubled, in subpixels^2): (x1-x0)*(y2-y0)-(x2-x0)*(y1-y0), evaluated
// exactly and then converted to double (the sign is exact). < 0 is front-facing (counter-clockwise
// in NDC, y up), > 0 back-facing, 0 degenerate.
double signed_area2(const ScreenTri& tri);

}  // namespace lr::ref
