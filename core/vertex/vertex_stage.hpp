// The vertex stage of one draw: model space to clip space, lighting in world space, projection
// and snapping to the subpixel lattice of the display.
//
// A VertexStage holds the draw's matrices (model-view-projection, normal matrix) and the
// viewport it projects into. transform() fills the vertex store entries of a mesh; the front end
// then lights lit Gouraud vertices on first use by a drawn triangle (light()), and clips the
// triangles that cross a plane from the clip coordinates (clip()), recomputed from the mesh.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/lighting/object_lights.hpp"
#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/rigid.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/vertex/clip.hpp"
#include "lineraster/core/vertex/screen_transform.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "lineraster/core/vertex/surface_vertex.hpp"

namespace lr {

// Model-space vector times a normal matrix (Q16.16 entries) as int64, then normalised. Inline:
// where the vector is a Normal16 the compiler multiplies 32 x 32 bits instead of 64 x 64.
inline Unit30 transform_normal(const Mat4& nm, int64_t x, int64_t y, int64_t z) {
  int64_t r[3];
  for (int i = 0; i < 3; ++i)
    r[i] = int64_t{nm.m[i][0].raw} * x + int64_t{nm.m[i][1].raw} * y + int64_t{nm.m[i][2].raw} * z;
  Unit30 u{0, 0, 1 << 30};
  normalize_unit30(r[0], r[1], r[2], u);
  return u;
}
// The same out of line, for the paths that are not per lit vertex (Phong surfaces, face
// normals): one copy of the code.
Unit30 transform_normal_call(const Mat4& nm, int64_t x, int64_t y, int64_t z);

// Face normal of a model-space triangle as a Q1.30 unit vector (counter-clockwise winding).
inline Unit30 face_normal_model(Vec3 p0, Vec3 p1, Vec3 p2) {
  int64_t e1[3] = {int64_t{p1.x.raw} - p0.x.raw, int64_t{p1.y.raw} - p0.y.raw,
                   int64_t{p1.z.raw} - p0.z.raw};
  int64_t e2[3] = {int64_t{p2.x.raw} - p0.x.raw, int64_t{p2.y.raw} - p0.y.raw,
                   int64_t{p2.z.raw} - p0.z.raw};
  // Edges are < 2^32; bring them below 2^30 so the cross products stay below 2^61.
  uint64_t m = 0;
  for (int i = 0; i < 3; ++i) m |= abs64(e1[i]) | abs64(e2[i]);
  if (m >= (uint64_t{1} << 30)) {
    int s = (63 - clz64(m)) - 29;
    for (int i = 0; i < 3; ++i) {
      e1[i] >>= s;
      e2[i] >>= s;
    }
  }
  Unit30 u{0, 0, 1 << 30};
  normalize_unit30(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0], u);
  return u;
}

constexpr Unit30 negate(Unit30 u) {
  return {-u.x, -u.y, -u.z};
}

// Lighting that reads the surface position (point lights, the local viewer): light_point_at.
// The front end hands it to the vertex stage through this pointer, which a renderer whose span
// set admits no such draw leaves nullptr (it then links no point lighting; renderer.hpp).
using PointLightFn = LitColor (*)(const PreparedLighting& pl, const Unit30& n, const Mat4* model,
                                  Vec3 p);
// light_point_split at p (world), or at model * p where model is given (a vertex's model-space
// position): the transform is the routine's, so that a renderer that leaves it out (nullptr)
// links neither.
LitColor light_point_at(const PreparedLighting& pl, const Unit30& n, const Mat4* model, Vec3 p);

// The model-view-projection of a draw with a fine model: P (V M) in FineMat4 products (P the
// camera's fine_projection, or its projection when it has none; V its view), composed once per
// draw. Reached only through Renderer::draw(mesh, FineMat4, ...), which hands the front end this
// function (FineComposeFn): an image that never draws a fine model links no FineMat4 product.
FineMat4 fine_model_view_projection(const Camera& camera, const FineMat4& model);
using FineComposeFn = FineMat4 (*)(const Camera&, const FineMat4&);

class VertexStage;
struct VertexColors;
// VertexStage::attributes, for the vertices of textured and Phong draws: called through this
// pointer, which a renderer without textured and Phong spans leaves nullptr (renderer.hpp).
using AttributesFn = void (VertexStage::*)(const Mesh& mesh, const VertexColors& colors, size_t i,
                                           ScreenVertex& sv, SurfaceVertex* surface,
                                           TexVertex* tex) const;

// How a draw's vertices get their colour (the front end decides it from the draw state).
struct VertexColors {
  bool lit = false;            // lit by the light set (else the mesh's colours or the material's)
  bool pending = false;        // lit Gouraud: lit on first use by a drawn triangle (light())
  bool split = false;          // primary and secondary colours apart (textured, modulated)
  bool surfaces = false;       // Phong: world normal, position, tangent into the surface store
  bool need_position = false;  // the lighting reads the world position
  bool tangents = false;       // Phong with a normal map
  Color15 material{};          // unlit meshes without vertex colours
  const PreparedLighting* lighting = nullptr;  // lit draws
  // Lit Gouraud draws of directional lights under a rigid model matrix: the lights in model
  // space (VertexStage::object_lights), else nullptr.
  const ObjectLights* object = nullptr;  // need_position: the lighting (never nullptr then).
  PointLightFn point = nullptr;
  // Textured and Phong draws: their vertices' attributes (VertexStage::attributes; never
  // nullptr when the transform is given surfaces or texture entries).
  AttributesFn attributes = nullptr;
};

// What VertexStage::transform() did: the vertices the exact path projected (the short path's
// range or precision did not reach them), and the OR of every vertex's outcode (0: no triangle
// of the draw needs the clipper).
struct TransformSummary {
  uint32_t wide = 0;
  uint8_t outcodes = 0;
};

// A model-space tangent (Q1.14) to world space (the model's upper 3x3), unit Q1.14.
void transform_tangent(const Mat4& model, const Tangent16& t, int16_t out[3]);

// VertexStage::light_face, for flat shading: the front end calls it through this pointer, which
// a renderer whose span set admits no flat-shaded draw leaves nullptr (it then links no face
// lighting; core/raster/renderer.hpp).
using FaceLightFn = LitColor (VertexStage::*)(VertexColors, const Vec3&, const Vec3&, const Vec3&,
                                              bool) const;

// VertexStage::light<kSpecular, kWorld>, as the front end calls it: the renderer picks the one of
// its features (RendererFeatures::specular, world_lighting; core/raster/renderer.hpp).
using LightFn = LitColor (*)(const VertexStage&, const Mesh&, VertexColors, size_t, bool);

class VertexStage {
 public:
  // bound: every coordinate of the positions the stage will transform lies in [-bound - 1,
  // bound] (position_bound); the default takes any (the short path then has less precision).
  // position_frac: the positions' fraction bits (Mesh::position_frac, in [16, 30]). fine_model
  // and compose: a draw with a FineMat4 model (model its rounding to Q16.16, which the lighting
  // reads) takes compose(camera, *fine_model) as its model-view-projection
  // (fine_model_view_projection); without them the Q16.16 product camera.projection *
  // camera.view * model, as before fine transforms (the same integers).
  VertexStage(const Camera& camera, const Mat4& model, GuardBand guard, int width, int height,
              uint32_t bound = 0x7FFFFFFFu, int position_frac = 16,
              const FineMat4* fine_model = nullptr, FineComposeFn compose = nullptr);

  // The draw's model-view-projection as the stage takes it: fine_model_view_projection(camera,
  // *fine_model) when a fine model is given, else the Q16.16 product as a FineMat4 of frac 16.
  static FineMat4 model_view_projection(const Camera& camera, const Mat4& model,
                                        const FineMat4* fine_model);

  // The mesh's vertices into out[0, n) (and surfaces[0, n) for Phong, tex[0, n) for draws
  // with texture coordinates; else nullptr): transformed, clip-tested (outcode), projected and
  // snapped when inside every plane.
  TransformSummary transform(const Mesh& mesh, const VertexColors& colors, ScreenVertex* out,
                             SurfaceVertex* surfaces, TexVertex* tex) const {
    return transform_range(mesh, colors, 0, mesh.positions.size(), out, surfaces, tex);
  }
  // Mesh vertices [first, first + count) into out[0, count) (surfaces, tex likewise), as
  // transform(): the one copy of the per-vertex code, for whole meshes and the vertex cache's
  // misses (FrontEnd::cache_corners, count 1).
  [[gnu::noinline]] TransformSummary transform_range(const Mesh& mesh, const VertexColors& colors,
                                                     size_t first, size_t count, ScreenVertex* out,
                                                     SurfaceVertex* surfaces, TexVertex* tex) const;

  // The directional lights of pl in model space into out when the model matrix is rigid (false:
  // it is not, and lighting stays in world space), by `prepare` (prepare_object_lights, or
  // prepare_diffuse_object_lights for lighting without specular products).
  bool object_lights(const PreparedLighting& pl, ObjectLights& out,
                     PrepareObjectLightsFn prepare = &prepare_object_lights) const {
    if (!rigid_) return false;
    prepare(pl, rot_, out);
    return true;
  }

  // Lit colour(s) of mesh vertex i, with the normal negated or not (two-sided back faces): the
  // secondary colour apart when colors.split, else 0. Out of line: one copy for its callers (the
  // front end's lighting on first use, back faces), which reach it through LightFn.
  // kSpecular false: without the specular term (RendererFeatures::specular: the renderer
  // refuses materials with one), the same colours for diffuse materials; the directional paths
  // then link no power tables (point lights, through colors.point, keep theirs). kWorld false:
  // the model-space path alone (RendererFeatures::world_lighting: the renderer admits only
  // draws with colors.object and unit normals), the same colours for them.
  // (colors by value here and in light_face: the caller's copy stays in registers.) Static,
  // the stage its first argument: a plain function pointer (a pointer to a member function
  // costs code at every call).
  template <bool kSpecular = true, bool kWorld = true>
  [[gnu::noinline]] static LitColor light(const VertexStage& stage, const Mesh& mesh,
                                          VertexColors colors, size_t i, bool back);

  // The lit colour of a flat-shaded triangle (face normal, centroid) of model-space corners.
  // Out of line: its 64-bit locals stay off the triangle loop's frame. kSpecular as light().
  template <bool kSpecular = true>
  [[gnu::noinline]] LitColor light_face(VertexColors colors, const Vec3& p0, const Vec3& p1,
                                        const Vec3& p2, bool back) const;

  // The attributes of a vertex of a textured or Phong draw (texture coordinates; world normal,
  // position, tangent): out of the per-vertex loop, called through VertexColors::attributes.
  [[gnu::noinline]] void attributes(const Mesh& mesh, const VertexColors& colors, size_t i,
                                    ScreenVertex& sv, SurfaceVertex* surface, TexVertex* tex) const;

  ClipCoord clip(const Vec3& model_position) const {
    return transform_point(mvp_, model_position, position_frac_);
  }
  // A mesh position in Q16.16 (rounded from position_frac bits): what the lighting reads.
  Vec3 q16(const Vec3& p) const {
    if (position_frac_ == 16) return p;
    const int s = position_frac_ - 16;
    return {Fixed::from_raw(static_cast<int32_t>(shift_rounded(p.x.raw, s))),
            Fixed::from_raw(static_cast<int32_t>(shift_rounded(p.y.raw, s))),
            Fixed::from_raw(static_cast<int32_t>(shift_rounded(p.z.raw, s)))};
  }
  // Projects and snaps a clip-space point inside every plane; false when w <= 0.
  bool project(const ClipCoord& c, ScreenVertex& v) const;
  // A mesh normal in world space, unit Q1.30. Under a rigid model matrix a rotation and one
  // Newton step (core/math/rigid.hpp), else (or for a normal that is not unit) exactly.
  Unit30 world_normal(const Normal16& n) const {
    Unit30 u;
    if (rigid_ && rotate_unit_normal(rot_, n, u)) return u;
    return transform_normal(nm_, n.x, n.y, n.z);
  }
  GuardBand guard() const { return guard_; }

 private:
  const Mat4& model_;
  FineMat4 mvp_;
  int32_t position_frac_;
  Mat4 nm_;
  NormalRotation rot_;  // nm_'s rows normalised, when rigid_
  bool rigid_ = false;
  // The exact path of one vertex (64-bit clip coordinates, outcode, project): out of the
  // per-vertex loop.
  [[gnu::noinline]] void project_exact(const Vec3& p, ScreenVertex& sv) const;
  GuardBand guard_;
  int32_t width_, height_;
  ScreenTransform screen_;  // the short path (after mvp_: made from it)
};

// Facing of a clip-space triangle from the sign of det[x y w] (homogeneous: valid for the part
// in front of the eye even when a vertex is behind it): true when front-facing, i.e.
// counter-clockwise in NDC (front_facing() in screen_vertex.hpp is the same rule on the display).
bool front_facing_clip(const ClipCoord (&c)[3]);

}  // namespace lr
