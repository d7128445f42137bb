// The camera of a frame, and its matrices with the meaning of gluPerspective and gluLookAt
// (docs/conventions.md#coordinates).
#pragma once

#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/vec.hpp"

namespace lr {

// View and projection matrices (OpenGL meaning), and the eye position in world space (for the
// local viewer).
struct Camera {
  Mat4 view = Mat4::identity();
  Mat4 projection = Mat4::identity();
  Vec3 eye{};
};

// fovy_degrees in (0, 180), aspect > 0, 0 < near < far; all Q16.16. Depth maps near -> -1 and
// far -> +1 in NDC. Returns false for arguments outside those ranges (out unchanged).
bool perspective(Fixed fovy_degrees, Fixed aspect, Fixed near, Fixed far, Mat4& out);

// View matrix looking from eye towards target with up roughly up. Returns false when
// eye == target or up is parallel to the view direction (out unchanged).
bool look_at(Vec3 eye, Vec3 target, Vec3 up, Mat4& out);

}  // namespace lr
