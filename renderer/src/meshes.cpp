// Procedural mesh builders (see scene.h). Every triangle is counter-clockwise seen from outside:
// cross(p1 - p0, p2 - p0) points along the outward normal.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {
namespace {

std::uint32_t vertexCount(const Mesh& mesh) { return static_cast<std::uint32_t>(mesh.vertices.size()); }

// Appends a quad (a, b, c, d counter-clockwise about `normal`) as two triangles.
void addQuad(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal) {
  const std::uint32_t base = vertexCount(mesh);
  for (const glm::vec3& p : {a, b, c, d}) mesh.vertices.push_back({p, normal});
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
}

}  // namespace

Mesh makeBox(glm::vec3 halfExtents) {
  if (!(halfExtents.x > 0.0f) || !(halfExtents.y > 0.0f) || !(halfExtents.z > 0.0f))
    throw std::invalid_argument("makeBox: half extents must be positive");
  Mesh mesh;
  mesh.vertices.reserve(24);
  mesh.indices.reserve(36);
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = sign;
      // u x v == n: for +axis use (e[axis+1], e[axis+2]); for -axis swap them.
      glm::vec3 u(0.0f), v(0.0f);
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = 1.0f;
      if (sign < 0.0f) std::swap(u, v);
      const glm::vec3 c = n * halfExtents;
      const glm::vec3 du = u * halfExtents;
      const glm::vec3 dv = v * halfExtents;
      addQuad(mesh, c - du - dv, c + du - dv, c + du + dv, c - du + dv, n);
    }
  }
  return mesh;
}

Mesh makeCylinder(float radius, float height, std::uint32_t segments) {
  if (segments < 3) throw std::invalid_argument("makeCylinder: needs at least 3 segments");
  if (!(radius > 0.0f) || !(height > 0.0f))
    throw std::invalid_argument("makeCylinder: radius and height must be positive");

  Mesh mesh;
  // Ring point at angle t: (r sin t, y, r cos t); t grows counter-clockwise seen from +Y.
  auto dir = [segments](std::uint32_t i) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(i % segments) / static_cast<double>(segments);
    return glm::vec3(static_cast<float>(std::sin(t)), 0.0f, static_cast<float>(std::cos(t)));
  };

  // Side: segments + 1 columns (seam duplicated), bottom/top pairs with smooth radial normals.
  const std::uint32_t sideBase = vertexCount(mesh);
  for (std::uint32_t i = 0; i <= segments; ++i) {
    const glm::vec3 n = dir(i);
    mesh.vertices.push_back({n * radius, n});
    mesh.vertices.push_back({n * radius + glm::vec3(0.0f, height, 0.0f), n});
  }
  for (std::uint32_t i = 0; i < segments; ++i) {
    const std::uint32_t b0 = sideBase + 2 * i, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
    for (std::uint32_t idx : {b0, b1, t1, b0, t1, t0}) mesh.indices.push_back(idx);
  }

  // Caps: a centre vertex plus a ring with a flat normal.
  for (const bool top : {true, false}) {
    const float y = top ? height : 0.0f;
    const glm::vec3 n(0.0f, top ? 1.0f : -1.0f, 0.0f);
    const std::uint32_t centre = vertexCount(mesh);
    mesh.vertices.push_back({glm::vec3(0.0f, y, 0.0f), n});
    for (std::uint32_t i = 0; i < segments; ++i)
      mesh.vertices.push_back({dir(i) * radius + glm::vec3(0.0f, y, 0.0f), n});
    for (std::uint32_t i = 0; i < segments; ++i) {
      const std::uint32_t a = centre + 1 + i, b = centre + 1 + (i + 1) % segments;
      if (top) {
        for (std::uint32_t idx : {centre, a, b}) mesh.indices.push_back(idx);
      } else {
        for (std::uint32_t idx : {centre, b, a}) mesh.indices.push_back(idx);
      }
    }
  }
  return mesh;
}

Mesh makeGroundPlane(float halfSize) {
  if (!(halfSize > 0.0f)) throw std::invalid_argument("makeGroundPlane: half size must be positive");
  Mesh mesh;
  const float h = halfSize;
  addQuad(mesh, {-h, 0.0f, -h}, {-h, 0.0f, h}, {h, 0.0f, h}, {h, 0.0f, -h}, {0.0f, 1.0f, 0.0f});
  return mesh;
}

}  // namespace s3d::renderer
