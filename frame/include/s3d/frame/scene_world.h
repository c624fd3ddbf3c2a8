#pragma once
// The renderer's scene as comfort's world: comfort knows no renderer type, the frame library knows both.
#include <vector>

#include "s3d/comfort/world_queries.h"
#include "s3d/renderer/scene.h"

namespace s3d::frame {

// The world layer's objects of `scene` as world meshes viewing its vertex arrays (the first-person layer, the
// weapon, is not part of the world); valid while the scene is. Throws std::out_of_range for an object whose mesh
// index is outside the scene.
std::vector<comfort::WorldMesh> worldMeshes(const renderer::Scene& scene);

}  // namespace s3d::frame
