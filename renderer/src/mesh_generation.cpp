#include "mesh_generation.h"

#include <cmath>
#include <vector>

namespace s3d::renderer {


void generateNormals(Mesh& mesh) {
  for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    Vertex& a = mesh.vertices[mesh.indices[t]];
    Vertex& b = mesh.vertices[mesh.indices[t + 1]];
    Vertex& c = mesh.vertices[mesh.indices[t + 2]];
    const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
    a.normal += n;
    b.normal += n;
    c.normal += n;
  }
  for (Vertex& v : mesh.vertices) v.normal = glm::length(v.normal) > 0.0f ? glm::normalize(v.normal) : glm::vec3(0, 1, 0);
}

// Per-vertex tangents from the texture-coordinate gradients of the triangles around each vertex (Lengyel's
// method), for normal-mapped primitives without TANGENT. glTF normal maps point green up the image, towards -v
// (v = 0 is the top row): the handedness puts the bitangent on the side of -v.
void generateTangents(Mesh& mesh) {
  std::vector<glm::vec3> tangent(mesh.vertices.size(), glm::vec3(0.0f)), bitangent(mesh.vertices.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::vec3 e1 = mesh.vertices[i1].position - mesh.vertices[i0].position;
    const glm::vec3 e2 = mesh.vertices[i2].position - mesh.vertices[i0].position;
    const glm::vec2 d1 = mesh.texCoords[i1] - mesh.texCoords[i0];
    const glm::vec2 d2 = mesh.texCoords[i2] - mesh.texCoords[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-12f) continue;  // degenerate texture mapping: no direction to contribute
    const glm::vec3 du = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 dv = (e2 * d1.x - e1 * d2.x) / det;
    for (std::uint32_t i : {i0, i1, i2}) {
      tangent[i] += du;
      bitangent[i] += dv;
    }
  }
  mesh.tangents.resize(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const glm::vec3 n = mesh.vertices[v].normal;
    glm::vec3 t = tangent[v] - n * glm::dot(n, tangent[v]);
    if (glm::length(t) < 1e-12f) t = glm::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
    t = glm::normalize(t);
    const float handedness = glm::dot(glm::cross(n, t), -bitangent[v]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[v] = glm::vec4(t, handedness);
  }
}

}  // namespace s3d::renderer
