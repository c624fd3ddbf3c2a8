// DeferredRenderer::setScene and updateGeometry: the scene checked, its vertices, indices, textures and objects
// uploaded, the opaque draw order and the G-buffer's visibility target and pipelines kept to the scene.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "deferred_renderer_impl.h"

namespace s3d::renderer {

glm::uvec2 DeferredRenderer::Impl::visibilityPackingFor(const Scene& scene) {
  std::uint64_t mostTriangles = 0;
  for (const Mesh& mesh : scene.meshes) mostTriangles = std::max<std::uint64_t>(mostTriangles, mesh.indices.size() / 3);
  return gpu::visibilityPacking(scene.objects.size(), mostTriangles);
}

void DeferredRenderer::Impl::setScene(const Scene& newScene) {
  raycastBvhCurrent = false;
  surfaceTextureTable = {};
  surfaceTexels = {};
  std::vector<Vertex> vertices;
  std::vector<gpu::SurfaceVertex> surface;
  std::vector<std::uint32_t> indices;
  meshRanges.clear();
  for (const Mesh& mesh : newScene.meshes) {
    if (mesh.indices.size() % 3 != 0)
      throw std::invalid_argument("scene '" + newScene.name + "': a mesh's index count " +
                                  std::to_string(mesh.indices.size()) + " is not a multiple of 3 (triangles)");
    meshRanges.push_back({std::uint32_t(indices.size()), std::uint32_t(mesh.indices.size()), std::int32_t(vertices.size())});
    for (std::uint32_t index : mesh.indices)
      if (index >= mesh.vertices.size()) throw std::invalid_argument("scene '" + newScene.name + "': mesh index out of range");
    appendSurfaceVertices(newScene, mesh, surface);
    vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
    indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
  }
  for (const Object& object : newScene.objects) {
    if (object.mesh >= newScene.meshes.size())
      throw std::invalid_argument("scene '" + newScene.name + "': object refers to missing mesh " + std::to_string(object.mesh));
    validateTextures(newScene, object);
  }
  if (vertices.empty() || indices.empty()) throw std::invalid_argument("scene '" + newScene.name + "' has no geometry");
  if (newScene.objects.size() >= S3D_NO_OBJECT)  // the G-buffer holds 16-bit object indices (packMaterial)
    throw std::invalid_argument("scene '" + newScene.name + "' has " + std::to_string(newScene.objects.size()) +
                                " objects, more than " + std::to_string(S3D_NO_OBJECT - 1));
  if (newScene.ambientOcclusion && !(newScene.ambientOcclusionRadius > 0.0f && newScene.ambientOcclusionRadius < 1e4f))
    throw std::invalid_argument("scene '" + newScene.name + "': ambient-occlusion radius must be in (0, 1e4) world units");

  // Vertex and index buffers for the shadow maps' vertex input, storage buffers for geometry.vert and the
  // G-buffer resolve.
  constexpr VkBufferUsageFlags pulled = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  vertexBuffer = vk::createBuffer(context, vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | pulled,
                                  vk::MemoryLocation::Device);
  vk::uploadBuffer(context, vertexBuffer, std::as_bytes(std::span(vertices)));
  // Also a vertex buffer: cut-out shadow casters read their texture coordinates from it.
  surfaceBuffer = vk::createBuffer(context, surface.size() * sizeof(gpu::SurfaceVertex),
                                   VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | pulled, vk::MemoryLocation::Device);
  vk::uploadBuffer(context, surfaceBuffer, std::as_bytes(std::span(surface)));
  textures.clear();
  for (const Texture& texture : newScene.textures) textures.push_back(uploadTexture(texture));
  indexBuffer = vk::createBuffer(context, indices.size() * sizeof(std::uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT | pulled,
                                 vk::MemoryLocation::Device);
  vk::uploadBuffer(context, indexBuffer, std::as_bytes(std::span(indices)));
  objectBuffer = vk::createBuffer(context, std::max<std::size_t>(1, newScene.objects.size()) * sizeof(gpu::ObjectConstants),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryLocation::HostVisible);
  drawOrder.clear();
  for (std::uint32_t i = 0; i < newScene.objects.size(); ++i) {
    const float opacity = newScene.objects[i].material.opacity;
    if (!(opacity > 0.0f && opacity <= 1.0f))
      throw std::invalid_argument("scene '" + newScene.name + "': object " + std::to_string(i) + " has opacity " +
                                  std::to_string(opacity) + " outside (0, 1]");
    if (newScene.objects[i].material.isTransparent() && newScene.objects[i].layer == Layer::FirstPerson)
      throw std::invalid_argument("scene '" + newScene.name + "': transparent first-person objects are not supported");
    validateMaterialExtras(newScene, i);
  }
  // First-person objects first: they are nearest, so their depth rejects the world behind them early.
  for (Layer layer : {Layer::FirstPerson, Layer::World})
    for (std::uint32_t i = 0; i < newScene.objects.size(); ++i)
      if (newScene.objects[i].layer == layer && !newScene.objects[i].material.isTransparent()) drawOrder.push_back(i);
  drawBounds.clear();
  bool textured = false;
  for (std::uint32_t i : drawOrder) {
    const Object& object = newScene.objects[i];
    drawBounds.push_back(objectBounds(newScene.meshes[object.mesh], object.transform));
    textured = textured || detail::materialVariant(object.material) != 0;
  }
  fitGBufferToScene(newScene, textured);
  std::vector<std::uint32_t> meshTriangles;
  for (const MeshRange& range : meshRanges) meshTriangles.push_back(range.indexCount / 3);
  transparentPass->setScene(newScene, meshTriangles, textures, whiteTexture, flatNormalTexture);
  std::vector<detail::ShadowMeshRange> shadowRanges;
  for (const MeshRange& range : meshRanges) shadowRanges.push_back({range.firstIndex, range.indexCount, range.vertexOffset});
  shadows->setScene(newScene, vertexBuffer.buffer, indexBuffer.buffer, std::move(shadowRanges), shadowTextures());
  lighting->setScene(newScene);
  scene = newScene;
}

void DeferredRenderer::Impl::fitGBufferToScene(const Scene& newScene, bool textured) {
  const glm::uvec2 packing = visibilityShading ? visibilityPackingFor(newScene) : glm::uvec2(0);
  const VkFormat visibilityFormat = packing.y != 0 ? kWideVisibilityFormat : kNarrowVisibilityFormat;
  const bool newFormat = visibilityShading && (visibility.width == 0 || visibility.format != visibilityFormat);
  if (newFormat)
    visibility = vk::createImage(context, visibilityFormat, width, height,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  const bool surfaceTargets = textured || !visibilityShading;
  const bool newAttachments = surfaceTargets != surfaceTargetsBound;
  visibilityPacking = packing;
  surfaceTargetsBound = surfaceTargets;
  if (!gbufferPipelinesValid || newFormat || newAttachments) {
    for (vk::Unique<VkPipeline>& pipeline : gbufferPipelines) pipeline.reset();
    gbufferPipelinesValid = true;
  }
}

detail::ShadowTextures DeferredRenderer::Impl::shadowTextures() const {
  detail::ShadowTextures shadowTextures{surfaceBuffer.buffer, textureSampler, {}, whiteTexture.view};
  for (const vk::Image& texture : textures) shadowTextures.views.push_back(texture.view);
  return shadowTextures;
}

void DeferredRenderer::Impl::updateGeometry(const Scene& newScene) {
  requireSameTopology(newScene);
  raycastBvhCurrent = false;
  std::vector<Vertex> vertices;
  std::vector<gpu::SurfaceVertex> surface;
  for (const Mesh& mesh : newScene.meshes) {
    appendSurfaceVertices(newScene, mesh, surface);
    vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
  }
  vk::uploadBuffer(context, vertexBuffer, std::as_bytes(std::span(vertices)));
  vk::uploadBuffer(context, surfaceBuffer, std::as_bytes(std::span(surface)));
  drawBounds.clear();
  for (std::uint32_t i : drawOrder) drawBounds.push_back(objectBounds(newScene.meshes[newScene.objects[i].mesh], newScene.objects[i].transform));
  std::vector<std::uint32_t> meshTriangles;
  std::vector<detail::ShadowMeshRange> shadowRanges;
  for (const MeshRange& range : meshRanges) {
    meshTriangles.push_back(range.indexCount / 3);
    shadowRanges.push_back({range.firstIndex, range.indexCount, range.vertexOffset});
  }
  transparentPass->setScene(newScene, meshTriangles, textures, whiteTexture, flatNormalTexture);
  shadows->setScene(newScene, vertexBuffer.buffer, indexBuffer.buffer, std::move(shadowRanges),
                    shadowTextures());  // local maps redrawn
  scene.meshes = newScene.meshes;  // not a whole copy: that would copy every texture's pixels again
  scene.objects = newScene.objects;
}

void DeferredRenderer::Impl::requireSameTopology(const Scene& newScene) const {
  auto sameMesh = [](const Mesh& a, const Mesh& b) {
    return a.vertices.size() == b.vertices.size() && a.indices == b.indices && a.texCoords.size() == b.texCoords.size() &&
           a.tangents.size() == b.tangents.size();
  };
  auto sameObject = [](const Object& a, const Object& b) {
    return a.mesh == b.mesh && a.layer == b.layer && a.castsShadow == b.castsShadow &&
           a.material.baseColorTexture == b.material.baseColorTexture &&
           a.material.normalTexture == b.material.normalTexture && a.material.isTransparent() == b.material.isTransparent();
  };
  bool same = !meshRanges.empty() && newScene.meshes.size() == scene.meshes.size() &&
              newScene.objects.size() == scene.objects.size() && newScene.textures.size() == scene.textures.size();
  for (std::size_t i = 0; same && i < newScene.meshes.size(); ++i) same = sameMesh(newScene.meshes[i], scene.meshes[i]);
  for (std::size_t i = 0; same && i < newScene.objects.size(); ++i) same = sameObject(newScene.objects[i], scene.objects[i]);
  if (!same)
    throw std::invalid_argument("scene '" + newScene.name + "': updateGeometry needs the meshes, objects and textures of "
                                "the scene last set (only vertices and transforms may change); call setScene");
}

void DeferredRenderer::Impl::appendSurfaceVertices(const Scene& scene, const Mesh& mesh, std::vector<gpu::SurfaceVertex>& surface) {
  const std::size_t count = mesh.vertices.size();
  if ((!mesh.texCoords.empty() && mesh.texCoords.size() != count) || (!mesh.tangents.empty() && mesh.tangents.size() != count))
    throw std::invalid_argument("scene '" + scene.name + "': a mesh's texture coordinates or tangents do not match its " +
                                std::to_string(count) + " vertices");
  for (std::size_t v = 0; v < count; ++v)
    surface.push_back({mesh.texCoords.empty() ? glm::vec2(0.0f) : mesh.texCoords[v],
                       mesh.tangents.empty() ? glm::vec4(0.0f) : mesh.tangents[v]});
}

void DeferredRenderer::Impl::validateMaterialExtras(const Scene& scene, std::uint32_t objectIndex) {
  const Material& m = scene.objects[objectIndex].material;
  const std::string where = "scene '" + scene.name + "': object " + std::to_string(objectIndex) + " has ";
  if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f) || !(m.cutoutAlpha >= 0.0f && m.cutoutAlpha <= 1.0f))
    throw std::invalid_argument(where + "an alpha cutoff or cut-out alpha outside 0..1");
  if (m.isCutout() && m.isTransparent())
    throw std::invalid_argument(where + "a cut-out material that is also transparent (opacity < 1 or alpha blending)");
  for (int c = 0; c < 3; ++c)
    if (!(m.emissive[c] >= 0.0f && std::isfinite(m.emissive[c])))
      throw std::invalid_argument(where + "an emissive colour that is negative or not finite");
  for (const TextureTransform* t : {&m.baseColorTransform, &m.normalTransform})
    if (!std::isfinite(t->offset.x) || !std::isfinite(t->offset.y) || !std::isfinite(t->rotation) ||
        !std::isfinite(t->scale.x) || !std::isfinite(t->scale.y))
      throw std::invalid_argument(where + "a texture transform that is not finite");
}

void DeferredRenderer::Impl::validateTextures(const Scene& scene, const Object& object) {
  const Mesh& mesh = scene.meshes[object.mesh];
  auto check = [&](std::int32_t index, Texture::Encoding encoding, const char* role, bool needsTangents) {
    if (index == kNoTexture) return;
    const std::string where = "scene '" + scene.name + "': " + role + " texture " + std::to_string(index);
    if (index < 0 || std::size_t(index) >= scene.textures.size())
      throw std::invalid_argument(where + " does not exist (" + std::to_string(scene.textures.size()) + " textures)");
    const Texture& texture = scene.textures[std::size_t(index)];
    if (texture.width == 0 || texture.height == 0 || texture.rgba.size() != std::size_t(texture.width) * texture.height * 4)
      throw std::invalid_argument(where + " is empty or its pixel data does not match its size");
    if (texture.encoding != encoding)
      throw std::invalid_argument(where + (encoding == Texture::Encoding::Srgb ? " must be sRGB-encoded" : " must be linear"));
    if (mesh.texCoords.empty() || (needsTangents && mesh.tangents.empty()))
      throw std::invalid_argument(where + " is on a mesh without texture coordinates" + (needsTangents ? " or tangents" : ""));
  };
  check(object.material.baseColorTexture, Texture::Encoding::Srgb, "base color", false);
  check(object.material.normalTexture, Texture::Encoding::Linear, "normal", true);
}

}  // namespace s3d::renderer
