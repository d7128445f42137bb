// Double-precision vector helpers for the host side (mesh preparation, tangents, tests).
#pragma once

#include <cmath>

#include "lineraster/host_sim/formats/host_mesh.hpp"

namespace lr::host {

inline Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double length(const Vec3d& a) {
  return std::sqrt(dot(a, a));
}

}  // namespace lr::host
