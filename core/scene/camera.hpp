// The camera of a frame, and its matrices with the meaning of gluPerspective and gluLookAt
// (docs/conventions.md#coordinates).
#pragma once

#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/vec.hpp"

namespace lr {

// View and projection matrices (OpenGL meaning), and the eye position in world space (for the
// local viewer).
// Optional: fine_projection, the projection with more fraction bits (perspective_fine), or
// nullptr (the default). Draws of a FineMat4 model (Renderer::draw(mesh, FineMat4, ...)) compose
// it with the view and their model without rounding to Q16.16 (with projection when it is
// nullptr); draws of a Mat4 model take projection, as before. Keep projection the same transform
// (e.g. to_mat4(*fine_projection)). A pointer (the renderer copies the camera: 4 bytes, not 68,
// of its RAM): the matrix must stay valid until render() returns; begin_frame() refuses one whose
// frac is outside [16, 30] (kInvalidArgument). docs/numerics.md#fine-transforms.
struct Camera {
  Mat4 view = Mat4::identity();
  Mat4 projection = Mat4::identity();
  Vec3 eye{};
  const FineMat4* fine_projection = nullptr;
};

// fovy_degrees in (0, 180), aspect > 0, 0 < near < far; all Q16.16. Depth maps near -> -1 and
// far -> +1 in NDC. Returns false for arguments outside those ranges (out unchanged).
bool perspective(Fixed fovy_degrees, Fixed aspect, Fixed near, Fixed far, Mat4& out);

// perspective() with the aspect the viewport's integer ratio width / height (so that 4/3 is
// exact) and every entry as a fine matrix: computed in Q2.30 from sin_cos_q30 with exact
// integer divisions, rounded once to the finest fraction count that holds the largest entry
// (30 when every entry is below 2 in magnitude; 29 for fovy 60, near 1, far 10, whose
// 2 far near / (far - near) is 2.22). Entries are within a unit of that count of the exact
// ones, f = cot(fovy / 2) within a few units of 2^-30 (sin_cos_q30's). fovy_degrees in (0, 180),
// width and height in [1, 2^15], 0 < near < far: false outside those ranges, or where an entry
// would not fit Q16.16 (out unchanged). Intermediates: c 2^30 < 2^61, f < 2^46 (else refused) so
// f height < 2^61, (far + near) 2^30 < 2^62, 2 far near < 2^63.
bool perspective_fine(Fixed fovy_degrees, int width, int height, Fixed near, Fixed far,
                      FineMat4& out);

// View matrix looking from eye towards target with up roughly up. Returns false when
// eye == target or up is parallel to the view direction (out unchanged).
bool look_at(Vec3 eye, Vec3 target, Vec3 up, Mat4& out);

}  // namespace lr
