// Small fixed-size vector used for points, directions and RGB values alike.
#pragma once
#include <algorithm>
#include <cmath>

namespace dualight {

struct Vec3 {
  float x = 0.f, y = 0.f, z = 0.f;

  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
  constexpr Vec3 operator/(const Vec3& o) const { return {x / o.x, y / o.y, z / o.z}; }
  constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  Vec3& operator*=(const Vec3& o) { x *= o.x; y *= o.y; z *= o.z; return *this; }
  Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
  Vec3& operator/=(float s) { x /= s; y /= s; z /= s; return *this; }
};

constexpr Vec3 operator*(float s, const Vec3& v) { return v * s; }
constexpr float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalize(const Vec3& v) { return v / length(v); }
constexpr float max_component(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
constexpr float average(const Vec3& v) { return (v.x + v.y + v.z) * (1.f / 3.f); }
// Rec. 709 / sRGB luminance weights of linear RGB, and the luminance of a colour (the float
// weights are these doubles rounded once).
inline constexpr double kLuminanceWeights[3] = {0.2126, 0.7152, 0.0722};
constexpr float luminance(const Vec3& c) {
  return static_cast<float>(kLuminanceWeights[0]) * c.x + static_cast<float>(kLuminanceWeights[1]) * c.y +
         static_cast<float>(kLuminanceWeights[2]) * c.z;
}
constexpr bool is_black(const Vec3& v) { return v.x == 0.f && v.y == 0.f && v.z == 0.f; }
inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline Vec3 vmin(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 vmax(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

using Color = Vec3;  // linear RGB

}  // namespace dualight
