#include "transform.h"

#include <cmath>
#include <numbers>

namespace globular {

Mat4 Mat4::identity() {
    Mat4 out;
    for (int i = 0; i < 4; ++i) out(i, i) = 1.0f;
    return out;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
    Mat4 out;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += double(a(r, k)) * b(k, c);
            out(r, c) = float(sum);
        }
    }
    return out;
}

Vec4 transformPoint(const Mat4& a, Vec3 p) {
    auto row = [&](int r) { return a(r, 0) * p.x + a(r, 1) * p.y + a(r, 2) * p.z + a(r, 3); };
    return {row(0), row(1), row(2), row(3)};
}

Mat4 lookAt(Vec3 eye, Vec3 target) {
    const Vec3 forward = normalized(target - eye);
    Vec3 up{0, 1, 0};
    if (length(cross(forward, up)) < 1e-9) up = {0, 0, 1};
    const Vec3 side = normalized(cross(forward, up));
    const Vec3 trueUp = cross(side, forward);
    Mat4 out = Mat4::identity();
    const Vec3 rows[3] = {side, trueUp, -1.0 * forward};
    for (int r = 0; r < 3; ++r) {
        out(r, 0) = float(rows[r].x);
        out(r, 1) = float(rows[r].y);
        out(r, 2) = float(rows[r].z);
        out(r, 3) = float(-dot(rows[r], eye));
    }
    return out;
}

Mat4 perspective(double fovYDegrees, double aspect, double zNear, double zFar) {
    const double f = 1.0 / std::tan(fovYDegrees * std::numbers::pi / 360.0);
    Mat4 out;
    out(0, 0) = float(f / aspect);
    out(1, 1) = float(f);
    out(2, 2) = float((zFar + zNear) / (zNear - zFar));
    out(2, 3) = float(2.0 * zFar * zNear / (zNear - zFar));
    out(3, 2) = -1.0f;
    return out;
}

Mat4 orthographic(double left, double right, double bottom, double top, double zNear, double zFar) {
    Mat4 out = Mat4::identity();
    out(0, 0) = float(2.0 / (right - left));
    out(1, 1) = float(2.0 / (top - bottom));
    out(2, 2) = float(-2.0 / (zFar - zNear));
    out(0, 3) = float(-(right + left) / (right - left));
    out(1, 3) = float(-(top + bottom) / (top - bottom));
    out(2, 3) = float(-(zFar + zNear) / (zFar - zNear));
    return out;
}

}  // namespace globular
