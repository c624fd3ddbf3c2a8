#include "s3d/comfort/world_queries.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "s3d/renderer/deferred_renderer.h"

namespace s3d::comfort {
namespace {

void checkEmbree(RTCDevice device, const char* call) {
  RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) throw std::runtime_error(std::string(call) + " failed: Embree error " + std::to_string(int(error)));
}

}  // namespace

struct WorldQueries::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

WorldQueries::WorldQueries(const renderer::Scene& scene) : impl_(new Impl) {
  try {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device) throw std::runtime_error("rtcNewDevice failed: Embree error " + std::to_string(int(rtcGetDeviceError(nullptr))));
    impl_->scene = rtcNewScene(impl_->device);
    checkEmbree(impl_->device, "rtcNewScene");
    for (const renderer::Object& object : scene.objects) {
      if (object.layer != renderer::Layer::World) continue;  // the weapon is not part of the world
      const renderer::Mesh& mesh = scene.meshes.at(object.mesh);
      RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
      checkEmbree(impl_->device, "rtcNewGeometry");
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                   3 * sizeof(float), mesh.vertices.size()));
      auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                     3 * sizeof(unsigned), mesh.indices.size() / 3));
      if (!vertices || !indices) {
        rtcReleaseGeometry(geometry);
        checkEmbree(impl_->device, "rtcSetNewGeometryBuffer");
        throw std::runtime_error("rtcSetNewGeometryBuffer returned no buffer");
      }
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        glm::vec3 world = glm::vec3(object.transform * glm::vec4(mesh.vertices[i].position, 1.0f));
        std::memcpy(vertices + 3 * i, &world, sizeof(world));
      }
      std::copy(mesh.indices.begin(), mesh.indices.begin() + std::ptrdiff_t(mesh.indices.size() / 3 * 3), indices);
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(impl_->scene, geometry);
      rtcReleaseGeometry(geometry);  // the scene holds it now
      checkEmbree(impl_->device, "rtcAttachGeometry");
    }
    rtcCommitScene(impl_->scene);
    checkEmbree(impl_->device, "rtcCommitScene");
  } catch (...) {
    delete impl_;
    throw;
  }
}

WorldQueries::~WorldQueries() { delete impl_; }

std::optional<float> WorldQueries::castRay(glm::vec3 origin, glm::vec3 direction, float maxDistance) const {
  float length = glm::length(direction);
  if (!(length > 0.0f) || !std::isfinite(length) || !(maxDistance > 0.0f))
    throw std::invalid_argument("castRay: direction must be non-zero and finite, maxDistance positive");
  direction /= length;
  RTCRayHit query{};
  query.ray.org_x = origin.x;
  query.ray.org_y = origin.y;
  query.ray.org_z = origin.z;
  query.ray.dir_x = direction.x;
  query.ray.dir_y = direction.y;
  query.ray.dir_z = direction.z;
  query.ray.tnear = 0.0f;
  query.ray.tfar = maxDistance;
  query.ray.mask = std::numeric_limits<unsigned>::max();
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(impl_->scene, &context, &query);
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return query.ray.tfar;
}

CrosshairPlacement placeCrosshair(const WorldQueries& world, const renderer::Camera& camera, float defaultDistance,
                                  float margin) {
  if (!(defaultDistance > 0.0f) || !std::isfinite(defaultDistance))
    throw std::invalid_argument("crosshair distance must be positive and finite (got " + std::to_string(defaultDistance) + ")");
  // The aim is the view axis, so the distance along it is the crosshair's linear depth.
  glm::mat4 cameraToWorld = glm::inverse(renderer::cameraView(camera));
  glm::vec3 aim = -glm::vec3(cameraToWorld[2]);
  std::optional<float> hit = world.castRay(camera.position, aim, defaultDistance);
  if (!hit) return {defaultDistance, false};
  return {std::max(*hit - margin, camera.nearPlane), true};
}

}  // namespace s3d::comfort
