#include "s3d/frame/scene_world.h"

namespace s3d::frame {

std::vector<comfort::WorldMesh> worldMeshes(const renderer::Scene& scene) {
  std::vector<comfort::WorldMesh> world;
  for (const renderer::Object& object : scene.objects) {
    if (object.layer != renderer::Layer::World) continue;
    const renderer::Mesh& mesh = scene.meshes.at(object.mesh);
    world.push_back({mesh.vertices.empty() ? nullptr : &mesh.vertices.front().position, mesh.vertices.size(),
                     sizeof(renderer::Vertex), mesh.indices, object.transform});
  }
  return world;
}

}  // namespace s3d::frame
