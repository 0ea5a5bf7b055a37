// hotmesh core: a plain 2-vector of doubles, the coordinate type of curves in a plane:
// (x, y) for 2D cases, (r, z) in the meridional plane of an axisymmetric boundary.
#pragma once

#include <cmath>

namespace hotmesh::geometry {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2& operator+=(const Vec2& o) { x += o.x; y += o.y; return *this; }
  constexpr Vec2& operator-=(const Vec2& o) { x -= o.x; y -= o.y; return *this; }
  constexpr Vec2& operator*=(double s) { x *= s; y *= s; return *this; }
  friend constexpr bool operator==(const Vec2&, const Vec2&) = default;
};

constexpr Vec2 operator+(Vec2 a, const Vec2& b) { return a += b; }
constexpr Vec2 operator-(Vec2 a, const Vec2& b) { return a -= b; }
constexpr Vec2 operator-(const Vec2& a) { return {-a.x, -a.y}; }
constexpr Vec2 operator*(Vec2 a, double s) { return a *= s; }
constexpr Vec2 operator*(double s, Vec2 a) { return a *= s; }
constexpr Vec2 operator/(const Vec2& a, double s) { return {a.x / s, a.y / s}; }

constexpr double dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
/// z-component of the 3D cross product: positive if b is counter-clockwise from a.
constexpr double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }
/// a rotated by +90 degrees.
constexpr Vec2 perpendicular(const Vec2& a) { return {-a.y, a.x}; }
inline double norm(const Vec2& a) { return std::sqrt(dot(a, a)); }
inline double distance(const Vec2& a, const Vec2& b) { return norm(a - b); }
inline bool is_finite(const Vec2& a) { return std::isfinite(a.x) && std::isfinite(a.y); }

}  // namespace hotmesh::geometry
