// Double-precision reference renderer (tests and benchmarks only, never firmware).
//
// Follows the conventions of DESIGN.md section 4 (those of OpenGL) but evaluates everything
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
//   depth interpolated linearly in screen space, test LESS, then written.
#pragma once

#include <cstdint>
#include <vector>

#include "host_sim/host_mesh.hpp"
#include "tests/reference/ref_math.hpp"

namespace lr::ref {

// A directional light. direction: world space, from the surface towards the light (normalized
// by the renderer). The light's ambient, diffuse and specular colours all equal color.
struct RefLight {
  Vec3d direction{1, 1, 1};
  Vec3d color{1, 1, 1};
};

struct RefMaterial {
  Vec3d ambient{0.1, 0.1, 0.1};
  Vec3d diffuse{0.8, 0.8, 0.8};
  Vec3d specular{0.5, 0.5, 0.5};
  Vec3d emission{0, 0, 0};
  double shininess = 32;  // GL range [0, 128]
};

enum class RefShading { Flat, Gouraud };

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
};

struct RefFrame {
  int width = 0, height = 0;
  std::vector<Vec3d> color;    // final colour per pixel, [0, 1] (before byte rounding)
  std::vector<uint8_t> rgb8;   // round(255 * c) per channel, 3 bytes per pixel, row 0 = top
  std::vector<double> depth;   // window depth [0, 1]; 1.0 (cleared) where nothing drawn
  std::vector<int32_t> owner;  // index of the mesh triangle that wrote the pixel last, -1 = none

  size_t index(int x, int y) const {
    return static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
  }
};

// Renders mesh into out (resized to params.width x params.height and cleared first).
void render(const host::HostMesh& mesh, const RefParams& params, RefFrame& out);

// The lit colour (clamped to [0, 1]) of a surface point: OpenGL fixed-function lighting with
// params.material, params.lights, params.global_ambient and params.local_viewer.
// normal_world must be unit length; position_world is used only for the local viewer.
Vec3d light_point(const RefParams& params, const Vec3d& normal_world, const Vec3d& position_world);

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
