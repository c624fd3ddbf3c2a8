#include "s3d/comfort/world_queries.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace s3d::comfort {
namespace {

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "vertex buffer is written as RTC_FORMAT_FLOAT3");

const char* errorName(RTCError error) {
  switch (error) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
  }
  return "unknown RTCError";
}

// Embree reports errors through the device (or, for a device that could not be created, per thread with a
// null device): turn the first pending one into an exception naming the call that was just made.
void checkEmbree(RTCDevice device, const char* call) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE) throw std::runtime_error(std::string(call) + " failed: " + errorName(error));
}

// Owns one RTCGeometry until it is attached to the scene (which then holds its own reference).
struct GeometryRef {
  RTCGeometry handle;
  ~GeometryRef() {
    if (handle) rtcReleaseGeometry(handle);
  }
};

}  // namespace

struct WorldQueries::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Embree() = default;
  Embree(const Embree&) = delete;
  Embree& operator=(const Embree&) = delete;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

WorldQueries::WorldQueries(std::span<const WorldMesh> meshes) : embree_(std::make_unique<Embree>()) {
  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) checkEmbree(nullptr, "rtcNewDevice");
  if (!embree_->device) throw std::runtime_error("rtcNewDevice failed: no device and no error");
  RTCDevice device = embree_->device;
  embree_->scene = rtcNewScene(device);
  checkEmbree(device, "rtcNewScene");

  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const WorldMesh& mesh = meshes[m];
    const std::size_t triangleCount = mesh.indices.size() / 3;
    if (triangleCount == 0 || mesh.vertexCount == 0) continue;
    if (!mesh.positions)
      throw std::invalid_argument("world mesh " + std::to_string(m) + " has " + std::to_string(mesh.vertexCount) +
                                  " vertices but no positions");
    for (std::uint32_t index : mesh.indices)
      if (index >= mesh.vertexCount)
        throw std::invalid_argument("world mesh " + std::to_string(m) + " has triangle index " + std::to_string(index) +
                                    " beyond its " + std::to_string(mesh.vertexCount) + " vertices");

    const GeometryRef geometry{rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE)};
    checkEmbree(device, "rtcNewGeometry");
    auto* positions = static_cast<glm::vec3*>(rtcSetNewGeometryBuffer(
        geometry.handle, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3), mesh.vertexCount));
    checkEmbree(device, "rtcSetNewGeometryBuffer(vertex)");
    auto* triangles = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geometry.handle, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), triangleCount));
    checkEmbree(device, "rtcSetNewGeometryBuffer(index)");

    // Embree's buffers are padded for its 16-byte loads; glm::vec3 is three packed floats like RTC_FORMAT_FLOAT3.
    const auto* bytes = static_cast<const std::byte*>(mesh.positions);
    for (std::size_t i = 0; i < mesh.vertexCount; ++i) {
      glm::vec3 position;
      std::memcpy(&position, bytes + i * mesh.strideBytes, sizeof(position));  // any stride, any alignment
      positions[i] = glm::vec3(mesh.transform * glm::vec4(position, 1.0f));
    }
    for (std::size_t i = 0; i < 3 * triangleCount; ++i) triangles[i] = mesh.indices[i];

    rtcCommitGeometry(geometry.handle);
    checkEmbree(device, "rtcCommitGeometry");
    rtcAttachGeometry(embree_->scene, geometry.handle);
    checkEmbree(device, "rtcAttachGeometry");
  }
  rtcCommitScene(embree_->scene);
  checkEmbree(device, "rtcCommitScene");
}

WorldQueries::~WorldQueries() = default;

std::optional<float> WorldQueries::castRay(glm::vec3 origin, glm::vec3 direction, float maxDistance) const {
  const float length = glm::length(direction);
  if (!(length > 0.0f) || !std::isfinite(length))
    throw std::invalid_argument("castRay: the direction must be non-zero and finite");
  if (!(maxDistance > 0.0f)) throw std::invalid_argument("castRay: maxDistance must be positive");
  direction /= length;  // Embree measures tfar in units of the direction's length: normalized, it is metres

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
  rtcIntersect1(embree_->scene, &context, &query);
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return query.ray.tfar;
}

RayCast embreeRayCast(const WorldQueries& world) {
  return [&world](glm::vec3 origin, glm::vec3 direction, float maxDistance) {
    return world.castRay(origin, direction, maxDistance);
  };
}

}  // namespace s3d::comfort
