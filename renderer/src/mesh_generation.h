#pragma once
// Vertex attributes a file may leave out, derived from the mesh.
#include "s3d/renderer/scene.h"

namespace s3d::renderer {

// Smooth per-vertex normals from the triangles (area-weighted), for primitives without NORMAL.
void generateNormals(Mesh& mesh);

// Per-vertex tangents from the texture-coordinate gradients (Lengyel's method), for normal-mapped primitives
// without TANGENT; needs texCoords.
void generateTangents(Mesh& mesh);

}  // namespace s3d::renderer
