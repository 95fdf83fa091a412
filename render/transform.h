#pragma once
// 4x4 matrices for the camera and the light: column-major floats, as OpenGL takes them.
// Right-handed world with y up (the paper's ground normal is +y).

#include <array>

#include "vec3.h"

namespace globular {

struct Mat4 {
    std::array<float, 16> m{};  ///< column-major: element (row r, column c) is m[c * 4 + r]

    static Mat4 identity();
    float operator()(int row, int column) const { return m[column * 4 + row]; }
    float& operator()(int row, int column) { return m[column * 4 + row]; }
    friend Mat4 operator*(const Mat4& a, const Mat4& b);
};

/// A point after a projective transform, before the divide.
struct Vec4 {
    double x = 0, y = 0, z = 0, w = 1;
};

Vec4 transformPoint(const Mat4& matrix, Vec3 point);

/// World to view: the eye at @p eye looks along @p target - @p eye, +y up.
/// An exactly vertical view direction falls back to +z as "up" so the matrix stays finite.
Mat4 lookAt(Vec3 eye, Vec3 target);

/// View to clip, OpenGL conventions (depth -1..1). @param fovYDegrees vertical field of
/// view; @param aspect width / height; @param zNear, zFar > 0, world units.
Mat4 perspective(double fovYDegrees, double aspect, double zNear, double zFar);

/// View to clip for a box [left, right] x [bottom, top] x [-zNear, -zFar] in view space.
Mat4 orthographic(double left, double right, double bottom, double top, double zNear, double zFar);

}  // namespace globular
