// Tests for the procedural meshes, the built-in scenes and their camera paths (renderer/src/meshes.cpp, scenes.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/scene.h"

namespace s3d::renderer {
namespace {

constexpr float kAspect = 16.0f / 9.0f;  // the renderer's image aspect

glm::vec3 triangleCross(const Mesh& mesh, std::size_t firstIndex) {
  const glm::vec3 p0 = mesh.vertices[mesh.indices[firstIndex]].position;
  const glm::vec3 p1 = mesh.vertices[mesh.indices[firstIndex + 1]].position;
  const glm::vec3 p2 = mesh.vertices[mesh.indices[firstIndex + 2]].position;
  return glm::cross(p1 - p0, p2 - p0);
}

// Every triangle's geometric normal (from its winding) must agree with each of its vertex normals.
void expectWindingMatchesNormals(const Mesh& mesh) {
  ASSERT_EQ(mesh.indices.size() % 3, 0u);
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::vec3 c = triangleCross(mesh, t);
    ASSERT_GT(glm::length(c), 0.0f) << "degenerate triangle " << t / 3;
    const glm::vec3 g = glm::normalize(c);
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_GT(glm::dot(g, mesh.vertices[mesh.indices[t + k]].normal), 0.0f) << "triangle " << t / 3;
  }
}

void expectIndicesInRange(const Mesh& mesh) {
  ASSERT_FALSE(mesh.indices.empty());
  EXPECT_EQ(mesh.indices.size() % 3, 0u);
  for (std::uint32_t i : mesh.indices) EXPECT_LT(i, mesh.vertices.size());
}

struct Triangle {
  glm::vec3 a, b, c;
};

std::vector<Triangle> trianglesOfLayer(const Scene& scene, Layer layer) {
  std::vector<Triangle> out;
  for (const Object& o : scene.objects) {
    if (o.layer != layer) continue;
    const Mesh& mesh = scene.meshes.at(o.mesh);
    auto xf = [&](std::uint32_t i) { return glm::vec3(o.transform * glm::vec4(mesh.vertices[i].position, 1.0f)); };
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
      out.push_back({xf(mesh.indices[t]), xf(mesh.indices[t + 1]), xf(mesh.indices[t + 2])});
  }
  return out;
}

// Moller-Trumbore, both faces; returns the distance along a unit direction.
std::optional<float> intersect(const Triangle& tri, glm::vec3 origin, glm::vec3 dir) {
  const glm::vec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const glm::vec3 p = glm::cross(dir, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return std::nullopt;
  const float inv = 1.0f / det;
  const glm::vec3 s = origin - tri.a;
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return std::nullopt;
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(dir, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return std::nullopt;
  const float t = glm::dot(e2, q) * inv;
  if (t <= 0.0f) return std::nullopt;
  return t;
}

std::optional<float> closestHit(const std::vector<Triangle>& tris, glm::vec3 origin, glm::vec3 dir) {
  std::optional<float> best;
  for (const Triangle& tri : tris)
    if (auto t = intersect(tri, origin, dir); t && (!best || *t < *best)) best = t;
  return best;
}

// View-space ray direction (unit) through the centre of pixel (x, y) of a width x height image, row 0 at the top.
glm::vec3 viewRay(int x, int y, int width, int height, float verticalFov) {
  const float tanHalf = std::tan(0.5f * verticalFov);
  const float ndcX = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width)) - 1.0f;
  const float ndcY = 1.0f - (2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height));
  return glm::normalize(glm::vec3(ndcX * tanHalf * kAspect, ndcY * tanHalf, -1.0f));
}

glm::mat3 cameraRotation(const Camera& cam) {
  const glm::mat4 r = glm::rotate(glm::rotate(glm::mat4(1.0f), cam.yawRadians, glm::vec3(0.0f, 1.0f, 0.0f)),
                                  cam.pitchRadians, glm::vec3(1.0f, 0.0f, 0.0f));
  return glm::mat3(r);
}

// --- Meshes -------------------------------------------------------------------------------------

TEST(Meshes, BoxHasTwentyFourVerticesAndThirtySixIndices) {
  const Mesh box = makeBox({1.0f, 2.0f, 3.0f});
  EXPECT_EQ(box.vertices.size(), 24u);
  EXPECT_EQ(box.indices.size(), 36u);
}

TEST(Meshes, BoxNormalsAreUnitAndOutward) {
  // Tolerance: |length - 1| <= 1e-6; each face's centre (mean of its triangles' vertices) has dot(n, centre) > 0.
  const glm::vec3 half{0.5f, 1.5f, 2.0f};
  const Mesh box = makeBox(half);
  for (const Vertex& v : box.vertices) {
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-6f);
    // Flat face normals: the vertex sits on the face plane the normal points out of.
    EXPECT_NEAR(glm::dot(v.position, v.normal), glm::dot(glm::abs(v.normal), half), 1e-6f);
  }
  for (std::size_t t = 0; t < box.indices.size(); t += 3) {
    const glm::vec3 centre = (box.vertices[box.indices[t]].position + box.vertices[box.indices[t + 1]].position +
                              box.vertices[box.indices[t + 2]].position) / 3.0f;
    EXPECT_GT(glm::dot(box.vertices[box.indices[t]].normal, centre), 0.0f);
  }
}

TEST(Meshes, BoxCoversItsHalfExtents) {
  const glm::vec3 half{0.25f, 1.0f, 4.0f};
  const Mesh box = makeBox(half);
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Vertex& v : box.vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  for (int a = 0; a < 3; ++a) {  // exact: the builder only multiplies by +-1
    EXPECT_FLOAT_EQ(lo[a], -half[a]);
    EXPECT_FLOAT_EQ(hi[a], half[a]);
  }
}

TEST(Meshes, BoxWindingAgreesWithNormals) { expectWindingMatchesNormals(makeBox({0.3f, 0.7f, 1.1f})); }

TEST(Meshes, CylinderWindingAgreesWithNormals) {
  expectWindingMatchesNormals(makeCylinder(0.5f, 2.0f, 3));
  expectWindingMatchesNormals(makeCylinder(1.0f, 1.0f, 32));
}

TEST(Meshes, GroundPlaneWindingAgreesWithNormals) { expectWindingMatchesNormals(makeGroundPlane(30.0f)); }

TEST(Meshes, CylinderSpansBaseToHeightWithinRadius) {
  // Tolerance 1e-5 m on heights and radii.
  const float radius = 0.4f, height = 2.5f;
  const Mesh cyl = makeCylinder(radius, height, 16);
  float minY = std::numeric_limits<float>::max(), maxY = -minY, maxR = 0.0f;
  for (const Vertex& v : cyl.vertices) {
    minY = std::min(minY, v.position.y);
    maxY = std::max(maxY, v.position.y);
    maxR = std::max(maxR, glm::length(glm::vec2(v.position.x, v.position.z)));
  }
  EXPECT_NEAR(minY, 0.0f, 1e-5f);
  EXPECT_NEAR(maxY, height, 1e-5f);
  EXPECT_NEAR(maxR, radius, 1e-5f);
}

TEST(Meshes, CylinderSideNormalsAreSmoothAndRadialAndCapsFlat) {
  // Tolerance 1e-5: side normals equal the normalized horizontal position; cap normals are exactly +-Y.
  const Mesh cyl = makeCylinder(0.75f, 1.0f, 12);
  for (const Vertex& v : cyl.vertices) {
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    if (std::abs(v.normal.y) < 0.5f) {
      const glm::vec3 radial = glm::normalize(glm::vec3(v.position.x, 0.0f, v.position.z));
      EXPECT_NEAR(glm::dot(radial, v.normal), 1.0f, 1e-5f);
    } else {
      EXPECT_FLOAT_EQ(std::abs(v.normal.y), 1.0f);
      EXPECT_NEAR(v.position.y, v.normal.y > 0.0f ? 1.0f : 0.0f, 1e-6f);
    }
  }
}

TEST(Meshes, CylinderRejectsBadArguments) {
  EXPECT_THROW(makeCylinder(1.0f, 1.0f, 2), std::invalid_argument);
  EXPECT_THROW(makeCylinder(1.0f, 1.0f, 0), std::invalid_argument);
  EXPECT_THROW(makeCylinder(0.0f, 1.0f, 8), std::invalid_argument);
  EXPECT_THROW(makeCylinder(-1.0f, 1.0f, 8), std::invalid_argument);
  EXPECT_THROW(makeCylinder(1.0f, 0.0f, 8), std::invalid_argument);
  EXPECT_THROW(makeCylinder(1.0f, -2.0f, 8), std::invalid_argument);
  EXPECT_THROW(makeCylinder(std::numeric_limits<float>::quiet_NaN(), 1.0f, 8), std::invalid_argument);
  EXPECT_NO_THROW(makeCylinder(1.0f, 1.0f, 3));
}

TEST(Meshes, BoxAndPlaneRejectNonPositiveSizes) {
  EXPECT_THROW(makeBox({0.0f, 1.0f, 1.0f}), std::invalid_argument);
  EXPECT_THROW(makeBox({1.0f, -1.0f, 1.0f}), std::invalid_argument);
  EXPECT_THROW(makeGroundPlane(0.0f), std::invalid_argument);
  EXPECT_THROW(makeGroundPlane(-5.0f), std::invalid_argument);
}

TEST(Meshes, GroundPlaneLiesAtZeroWithUpNormal) {
  const Mesh plane = makeGroundPlane(30.0f);
  EXPECT_EQ(plane.vertices.size(), 4u);
  for (const Vertex& v : plane.vertices) {
    EXPECT_EQ(v.position.y, 0.0f);
    EXPECT_EQ(v.normal, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(std::max(std::abs(v.position.x), std::abs(v.position.z)), 30.0f);
  }
}

TEST(Meshes, IndicesAreInRange) {
  expectIndicesInRange(makeBox(glm::vec3(1.0f)));
  expectIndicesInRange(makeCylinder(1.0f, 1.0f, 3));
  expectIndicesInRange(makeCylinder(1.0f, 1.0f, 64));
  expectIndicesInRange(makeGroundPlane(1.0f));
  for (const Mesh& m : makeCourtyardScene().meshes) expectIndicesInRange(m);
}

// --- Courtyard scene ----------------------------------------------------------------------------

TEST(Courtyard, HasBothLayers) {
  const Scene scene = makeCourtyardScene();
  EXPECT_EQ(scene.name, "courtyard");
  EXPECT_TRUE(scene.hasLayer(Layer::World));
  EXPECT_TRUE(scene.hasLayer(Layer::FirstPerson));
}

TEST(Courtyard, ObjectsReferenceExistingMeshes) {
  const Scene scene = makeCourtyardScene();
  for (const Object& o : scene.objects) EXPECT_LT(o.mesh, scene.meshes.size());
}

TEST(Courtyard, MeshesAreDeduplicated) {
  const Scene scene = makeCourtyardScene();
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    for (std::size_t j = i + 1; j < scene.meshes.size(); ++j) {
      const Mesh& a = scene.meshes[i];
      const Mesh& b = scene.meshes[j];
      const bool same = a.indices == b.indices && a.vertices.size() == b.vertices.size() &&
                        std::equal(a.vertices.begin(), a.vertices.end(), b.vertices.begin(),
                                   [](const Vertex& p, const Vertex& q) {
                                     return p.position == q.position && p.normal == q.normal;
                                   });
      EXPECT_FALSE(same) << "meshes " << i << " and " << j << " are identical";
    }
  // Every mesh is used by at least one object.
  for (std::uint32_t m = 0; m < scene.meshes.size(); ++m)
    EXPECT_TRUE(std::any_of(scene.objects.begin(), scene.objects.end(), [m](const Object& o) { return o.mesh == m; }))
        << "mesh " << m << " unused";
}

TEST(Courtyard, FirstPersonWeaponHasTwoToThreeParts) {
  const Scene scene = makeCourtyardScene();
  const auto n = std::count_if(scene.objects.begin(), scene.objects.end(),
                               [](const Object& o) { return o.layer == Layer::FirstPerson; });
  EXPECT_GE(n, 2);
  EXPECT_LE(n, 3);
}

TEST(Courtyard, AllWeaponVerticesLieInsideFirstPersonFrustum) {
  // Projection: glm::perspective(0.9, 16/9, 0.02, 4); |ndc.x|, |ndc.y| <= 0.98 (2% margin), view depth in [near, far].
  const Scene scene = makeCourtyardScene();
  const FirstPersonView& fp = scene.firstPerson;
  EXPECT_FLOAT_EQ(fp.verticalFovRadians, 0.9f);
  EXPECT_FLOAT_EQ(fp.nearPlane, 0.02f);
  EXPECT_FLOAT_EQ(fp.farPlane, 4.0f);
  const glm::mat4 proj = glm::perspective(fp.verticalFovRadians, kAspect, fp.nearPlane, fp.farPlane);
  for (const Object& o : scene.objects) {
    if (o.layer != Layer::FirstPerson) continue;
    for (const Vertex& v : scene.meshes[o.mesh].vertices) {
      const glm::vec4 view = o.transform * glm::vec4(v.position, 1.0f);
      const float depth = -view.z;
      EXPECT_GE(depth, fp.nearPlane);
      EXPECT_LE(depth, fp.farPlane);
      EXPECT_GE(depth, 0.25f);  // the weapon sits 0.25..0.6 m from the eye
      EXPECT_LE(depth, 0.6f);
      const glm::vec4 clip = proj * view;
      ASSERT_GT(clip.w, 0.0f);
      EXPECT_LE(std::abs(clip.x / clip.w), 0.98f) << "x=" << view.x << " z=" << view.z;
      EXPECT_LE(std::abs(clip.y / clip.w), 0.98f) << "y=" << view.y << " z=" << view.z;
      // Lower right of the view.
      EXPECT_GT(clip.x / clip.w, 0.0f);
      EXPECT_LT(clip.y / clip.w, 0.0f);
    }
  }
}

TEST(Courtyard, WeaponCoversFiveToTwelvePercentOfTheScreen) {
  // Ray-cast a 192 x 108 grid of pixel centres through the first-person projection.
  const Scene scene = makeCourtyardScene();
  const std::vector<Triangle> tris = trianglesOfLayer(scene, Layer::FirstPerson);
  constexpr int w = 192, h = 108;
  int hits = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (closestHit(tris, glm::vec3(0.0f), viewRay(x, y, w, h, scene.firstPerson.verticalFovRadians))) ++hits;
  const double coverage = static_cast<double>(hits) / (w * h);
  std::printf("weapon coverage %.4f\n", coverage);
  EXPECT_GE(coverage, 0.05);
  EXPECT_LE(coverage, 0.12);
}

TEST(Courtyard, CameraIsOutsideEveryObjectBoundingBox) {
  // The camera must be at least nearPlane (0.1 m) away from every world object's axis-aligned bounding box.
  const Scene scene = makeCourtyardScene();
  const glm::vec3 eye = scene.camera.position;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& o = scene.objects[i];
    if (o.layer != Layer::World) continue;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const Vertex& v : scene.meshes[o.mesh].vertices) {
      const glm::vec3 p(o.transform * glm::vec4(v.position, 1.0f));
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const glm::vec3 margin(scene.camera.nearPlane);
    const bool inside = glm::all(glm::greaterThanEqual(eye, lo - margin)) && glm::all(glm::lessThanEqual(eye, hi + margin));
    EXPECT_FALSE(inside) << "object " << i;
  }
}

TEST(Courtyard, CameraMatchesTheStereoTestSetup) {
  const Scene scene = makeCourtyardScene();
  EXPECT_NEAR(scene.camera.position.y, 1.7f, 1e-6f);
  EXPECT_NEAR(scene.camera.verticalFovRadians, 1.0f, 0.05f);
  EXPECT_FLOAT_EQ(scene.camera.nearPlane, 0.1f);
  EXPECT_FLOAT_EQ(scene.camera.farPlane, 1000.0f);
  EXPECT_FLOAT_EQ(scene.crosshairDistance, 8.0f);
  EXPECT_FLOAT_EQ(scene.exposure, 0.6f);
}

TEST(Courtyard, SkyIsVisibleInTheUpperHalfOfTheView) {
  // At least 50% of a 64 x 36 ray grid's upper half hits no world geometry (so the sky shows there).
  const Scene scene = makeCourtyardScene();
  const std::vector<Triangle> tris = trianglesOfLayer(scene, Layer::World);
  const glm::mat3 rot = cameraRotation(scene.camera);
  constexpr int w = 64, h = 36;
  int sky = 0;
  for (int y = 0; y < h / 2; ++y)
    for (int x = 0; x < w; ++x)
      if (!closestHit(tris, scene.camera.position, rot * viewRay(x, y, w, h, scene.camera.verticalFovRadians))) ++sky;
  std::printf("sky fraction of upper half %.3f\n", static_cast<double>(sky) / (w * h / 2));
  EXPECT_GE(static_cast<double>(sky) / (w * h / 2), 0.5);
}

TEST(Courtyard, VisibleDepthsSpanNearAndFarForParallax) {
  // On a 64 x 36 ray grid: the closest visible hit is 1.2..2.5 m away; some visible non-ground hit is >= 25 m away.
  const Scene scene = makeCourtyardScene();
  const std::vector<Triangle> tris = trianglesOfLayer(scene, Layer::World);
  const glm::mat3 rot = cameraRotation(scene.camera);
  const glm::vec3 forward = rot * glm::vec3(0.0f, 0.0f, -1.0f);
  constexpr int w = 64, h = 36;
  float nearest = std::numeric_limits<float>::max(), farthestAboveGround = 0.0f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 dir = rot * viewRay(x, y, w, h, scene.camera.verticalFovRadians);
      if (auto t = closestHit(tris, scene.camera.position, dir)) {
        const float depth = *t * glm::dot(dir, forward);
        nearest = std::min(nearest, depth);
        if ((scene.camera.position + *t * dir).y > 0.01f) farthestAboveGround = std::max(farthestAboveGround, depth);
      }
    }
  std::printf("nearest %.3f m, farthest above ground %.3f m\n", static_cast<double>(nearest), static_cast<double>(farthestAboveGround));
  EXPECT_GE(nearest, 1.2f);
  EXPECT_LE(nearest, 2.5f);
  EXPECT_GE(farthestAboveGround, 25.0f);
}

TEST(Courtyard, LightingIsValid) {
  // Sun direction unit within 1e-5; 2-3 point lights with radii 4..8 m; ambient 0.2..0.4 per channel.
  const Scene scene = makeCourtyardScene();
  EXPECT_NEAR(glm::length(scene.sun.directionToSun), 1.0f, 1e-5f);
  EXPECT_GT(scene.sun.directionToSun.y, 0.0f);
  EXPECT_GE(scene.pointLights.size(), 2u);
  EXPECT_LE(scene.pointLights.size(), 3u);
  for (const PointLight& l : scene.pointLights) {
    EXPECT_GE(l.radius, 4.0f);
    EXPECT_LE(l.radius, 8.0f);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_GE(scene.ambientColor[c], 0.2f);
    EXPECT_LE(scene.ambientColor[c], 0.4f);
  }
}

TEST(Courtyard, MaterialsAreInRangeAndVaried) {
  const Scene scene = makeCourtyardScene();
  float minGloss = 1.0f, maxGloss = 0.0f;
  for (const Object& o : scene.objects) {
    const Material& m = o.material;
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(m.albedo[c], 0.0f);
      EXPECT_LE(m.albedo[c], 1.0f);
      EXPECT_GE(m.specularColor[c], 0.0f);
      EXPECT_LE(m.specularColor[c], 1.0f);
    }
    EXPECT_GE(m.glossiness, 0.0f);
    EXPECT_LE(m.glossiness, 1.0f);
    minGloss = std::min(minGloss, m.glossiness);
    maxGloss = std::max(maxGloss, m.glossiness);
  }
  EXPECT_LE(minGloss, 0.2f);  // some matte
  EXPECT_GE(maxGloss, 0.8f);  // some glossy
}

TEST(BuiltInScenes, NamesContainCourtyard) {
  const std::vector<std::string> names = builtInSceneNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "courtyard"), names.end());
}

TEST(BuiltInScenes, MakeBuiltInSceneBuildsEveryListedScene) {
  for (const std::string& name : builtInSceneNames()) EXPECT_EQ(makeBuiltInScene(name).name, name);
}

TEST(BuiltInScenes, UnknownSceneThrowsNamingItAndTheChoices) {
  try {
    makeBuiltInScene("no-such-scene");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no-such-scene"), std::string::npos) << what;
    EXPECT_NE(what.find("courtyard"), std::string::npos) << what;
  }
}


// --- Stereo hard-case scenes (fence, cover, depth-range) and camera paths -------------------------

struct Aabb {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};
};

Aabb worldBounds(const Scene& scene, const Object& o) {
  Aabb box;
  for (const Vertex& v : scene.meshes.at(o.mesh).vertices) {
    const glm::vec3 p(o.transform * glm::vec4(v.position, 1.0f));
    box.lo = glm::min(box.lo, p);
    box.hi = glm::max(box.hi, p);
  }
  return box;
}

// Euclidean distance from p to the box (0 inside).
float distanceToBox(const Aabb& box, glm::vec3 p) {
  return glm::length(glm::max(glm::max(box.lo - p, p - box.hi), glm::vec3(0.0f)));
}

// Slab test of the ray origin + t dir (t > 0) against the box; handles flat boxes (the ground plane).
std::optional<float> rayBoxEntry(const Aabb& box, glm::vec3 origin, glm::vec3 dir) {
  float t0 = 0.0f, t1 = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dir[a]) < 1e-12f) {
      if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) return std::nullopt;
      continue;
    }
    float ta = (box.lo[a] - origin[a]) / dir[a], tb = (box.hi[a] - origin[a]) / dir[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return std::nullopt;
  }
  return t0;
}

// Sizes of the object's oriented box (its mesh's local bounds through the transform's axes), ascending.
std::array<float, 3> orientedSizes(const Scene& scene, const Object& o) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Vertex& v : scene.meshes.at(o.mesh).vertices) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  std::array<float, 3> sizes{};
  for (int a = 0; a < 3; ++a)
    sizes[static_cast<std::size_t>(a)] = (hi[a] - lo[a]) * glm::length(glm::vec3(o.transform[a]));
  std::sort(sizes.begin(), sizes.end());
  return sizes;
}

glm::vec3 forwardOf(const Camera& cam) { return cameraRotation(cam) * glm::vec3(0.0f, 0.0f, -1.0f); }

// Every camera a scene is seen from: `camera` and each frame of its path.
std::vector<Camera> allCameras(const Scene& scene) {
  std::vector<Camera> cams{scene.camera};
  cams.insert(cams.end(), scene.cameraPath.begin(), scene.cameraPath.end());
  return cams;
}

bool sameCamera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.yawRadians == b.yawRadians && a.pitchRadians == b.pitchRadians &&
         a.verticalFovRadians == b.verticalFovRadians && a.nearPlane == b.nearPlane && a.farPlane == b.farPlane;
}

// On a w x h ray grid from `cam`: the share of rays whose visible world hit has view depth in [minDepth, maxDepth]
// (and, with aboveGround, lies above y = 0.01).
double shareOfHitsInDepthRange(const Scene& scene, const Camera& cam, float minDepth, float maxDepth,
                               bool aboveGround) {
  const std::vector<Triangle> tris = trianglesOfLayer(scene, Layer::World);
  const glm::mat3 rot = cameraRotation(cam);
  const glm::vec3 forward = forwardOf(cam);
  constexpr int w = 64, h = 36;
  int count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 dir = rot * viewRay(x, y, w, h, cam.verticalFovRadians);
      const auto t = closestHit(tris, cam.position, dir);
      if (!t) continue;
      const float depth = *t * glm::dot(dir, forward);
      if (depth >= minDepth && depth <= maxDepth && (!aboveGround || (cam.position + *t * dir).y > 0.01f)) ++count;
    }
  return static_cast<double>(count) / (w * h);
}

TEST(SceneCatalog, ListsTheStereoHardCases) {
  const std::vector<std::string> names = builtInSceneNames();
  for (const char* name : {"courtyard", "fence", "cover", "depth-range"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(SceneCatalog, EveryBuiltInSceneBuildsWithBothLayers) {
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_TRUE(scene.hasLayer(Layer::World)) << name;
    EXPECT_TRUE(scene.hasLayer(Layer::FirstPerson)) << name;
    for (const Object& o : scene.objects) EXPECT_LT(o.mesh, scene.meshes.size()) << name;
  }
}

TEST(SceneCatalog, EveryCameraIsOutsideEveryWorldBoundingBoxByTheNearPlane) {
  // `camera` and every path frame: no world object's axis-aligned box, grown by nearPlane on every side, contains
  // the eye (so its Euclidean distance to each box is at least nearPlane too).
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    const std::vector<Camera> cams = allCameras(scene);
    for (std::size_t c = 0; c < cams.size(); ++c)
      for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        if (scene.objects[i].layer != Layer::World) continue;
        const Aabb box = worldBounds(scene, scene.objects[i]);
        const glm::vec3 margin(cams[c].nearPlane);
        const bool inside = glm::all(glm::greaterThanEqual(cams[c].position, box.lo - margin)) &&
                            glm::all(glm::lessThanEqual(cams[c].position, box.hi + margin));
        EXPECT_FALSE(inside) << name << ": camera " << c << " (0 = scene.camera, k = path frame k-1), object " << i;
      }
  }
}

TEST(SceneCatalog, EveryWeaponVertexLiesInsideTheFirstPersonFrustum) {
  // glm::perspective(fp fov, 16/9, fp near, fp far): |ndc.x|, |ndc.y| <= 0.98 (2% margin), depth in [near, far].
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    const FirstPersonView& fp = scene.firstPerson;
    const glm::mat4 proj = glm::perspective(fp.verticalFovRadians, kAspect, fp.nearPlane, fp.farPlane);
    for (const Object& o : scene.objects) {
      if (o.layer != Layer::FirstPerson) continue;
      for (const Vertex& v : scene.meshes[o.mesh].vertices) {
        const glm::vec4 view = o.transform * glm::vec4(v.position, 1.0f);
        EXPECT_GE(-view.z, fp.nearPlane) << name;
        EXPECT_LE(-view.z, fp.farPlane) << name;
        const glm::vec4 clip = proj * view;
        ASSERT_GT(clip.w, 0.0f) << name;
        EXPECT_LE(std::abs(clip.x / clip.w), 0.98f) << name << " x=" << view.x << " z=" << view.z;
        EXPECT_LE(std::abs(clip.y / clip.w), 0.98f) << name << " y=" << view.y << " z=" << view.z;
      }
    }
  }
}

TEST(SceneCatalog, CameraIsOneOfItsPathFrames) {
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    EXPECT_TRUE(std::any_of(scene.cameraPath.begin(), scene.cameraPath.end(),
                            [&](const Camera& c) { return sameCamera(c, scene.camera); }))
        << name;
  }
}

TEST(FenceScene, HasAtLeastTwentyThinOccludersTwoToFourMetresAhead) {
  // A thin occluder: its two smaller oriented sizes are < 5 cm and its longest >= 0.5 m (a slat, bar or wire), and
  // its centre is 2-4 m ahead of `camera` along the view axis.
  const Scene scene = makeBuiltInScene("fence");
  const glm::vec3 forward = forwardOf(scene.camera);
  int thin = 0;
  for (const Object& o : scene.objects) {
    if (o.layer != Layer::World) continue;
    const std::array<float, 3> sizes = orientedSizes(scene, o);
    const glm::vec3 centre(o.transform * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const float depth = glm::dot(centre - scene.camera.position, forward);
    if (sizes[1] < 0.05f && sizes[2] >= 0.5f && depth >= 2.0f && depth <= 4.0f) ++thin;
  }
  std::printf("thin occluders 2-4 m ahead: %d\n", thin);
  EXPECT_GE(thin, 20);
}

TEST(FenceScene, SlatGapsAreOneHalfToTwiceTheSlatWidth) {
  // Upright slats 2-4 cm wide (x extent of their bounding box), >= 1 m tall, < 5 cm deep: at least 20 neighbouring
  // pairs (sorted by x) whose gap is 0.5-2 slat widths.
  const Scene scene = makeBuiltInScene("fence");
  std::vector<Aabb> slats;
  for (const Object& o : scene.objects) {
    if (o.layer != Layer::World) continue;
    const Aabb box = worldBounds(scene, o);
    const glm::vec3 size = box.hi - box.lo;
    if (size.x >= 0.02f && size.x <= 0.04f && size.y >= 1.0f && size.z < 0.05f) slats.push_back(box);
  }
  ASSERT_GE(slats.size(), 21u);
  std::sort(slats.begin(), slats.end(), [](const Aabb& a, const Aabb& b) { return a.lo.x < b.lo.x; });
  int similarGaps = 0;
  for (std::size_t i = 0; i + 1 < slats.size(); ++i) {
    const float width = slats[i].hi.x - slats[i].lo.x;
    const float gap = slats[i + 1].lo.x - slats[i].hi.x;
    if (gap >= 0.5f * width && gap <= 2.0f * width) ++similarGaps;
  }
  EXPECT_GE(similarGaps, 20);
}

TEST(CoverScene, NearestWorldSurfaceAlongTheViewAxisIsUnderOneMetre) {
  // At the cover frame (`camera`), the ray along the view axis enters some world bounding box between the near
  // plane and 1 m (exact slab test).
  const Scene scene = makeBuiltInScene("cover");
  const glm::vec3 forward = forwardOf(scene.camera);
  float nearest = std::numeric_limits<float>::max();
  for (const Object& o : scene.objects)
    if (o.layer == Layer::World)
      if (auto t = rayBoxEntry(worldBounds(scene, o), scene.camera.position, forward))
        nearest = std::min(nearest, *t);
  std::printf("cover: nearest surface on the view axis %.3f m\n", static_cast<double>(nearest));
  EXPECT_LT(nearest, 1.0f);
  EXPECT_GE(nearest, scene.camera.nearPlane);
}

TEST(CoverScene, GeometryFiveToTwentyMetresAwayShowsPastTheWall) {
  // On a 64 x 36 ray grid at the cover frame: >= 30% of the view is world surface within 1 m (the wall), and >= 5%
  // is above-ground surface 5-20 m away.
  const Scene scene = makeBuiltInScene("cover");
  const double wall = shareOfHitsInDepthRange(scene, scene.camera, 0.0f, 1.0f, false);
  const double beyond = shareOfHitsInDepthRange(scene, scene.camera, 5.0f, 20.0f, true);
  std::printf("cover: within 1 m %.3f, above ground at 5-20 m %.3f\n", wall, beyond);
  EXPECT_GE(wall, 0.30);
  EXPECT_GE(beyond, 0.05);
}

TEST(CoverScene, PathWalksFromFourMetresIntoCoverAndBack) {
  // Distance from the eye to the wall's face (the nearest box entry straight ahead, yaw ignored): first and last
  // frames 4 m +- 5 cm, smallest 0.6 m +- 1 cm.
  const Scene scene = makeBuiltInScene("cover");
  auto wallDistance = [&scene](const Camera& cam) {
    float nearest = std::numeric_limits<float>::max();
    for (const Object& o : scene.objects)
      if (o.layer == Layer::World)
        if (auto t = rayBoxEntry(worldBounds(scene, o), cam.position, glm::vec3(0.0f, 0.0f, -1.0f)))
          nearest = std::min(nearest, *t);
    return nearest;
  };
  ASSERT_FALSE(scene.cameraPath.empty());
  float smallest = std::numeric_limits<float>::max();
  for (const Camera& cam : scene.cameraPath) smallest = std::min(smallest, wallDistance(cam));
  EXPECT_NEAR(wallDistance(scene.cameraPath.front()), 4.0f, 0.05f);
  EXPECT_NEAR(wallDistance(scene.cameraPath.back()), 4.0f, 0.05f);
  EXPECT_NEAR(smallest, 0.6f, 0.01f);
}

TEST(DepthRangeScene, SpansThirtyCentimetresToKilometresWithAHundredKilometreFarPlane) {
  // Distances from `camera` to world bounding boxes: some object within 0.5 m, some beyond 5 km;
  // near plane 0.1 m, far plane >= 100 km.
  const Scene scene = makeBuiltInScene("depth-range");
  float nearest = std::numeric_limits<float>::max(), farthest = 0.0f;
  for (const Object& o : scene.objects) {
    if (o.layer != Layer::World) continue;
    const float d = distanceToBox(worldBounds(scene, o), scene.camera.position);
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  std::printf("depth-range: nearest object %.3f m, farthest %.0f m\n", static_cast<double>(nearest),
              static_cast<double>(farthest));
  EXPECT_LE(nearest, 0.5f);
  EXPECT_GE(farthest, 5000.0f);
  EXPECT_FLOAT_EQ(scene.camera.nearPlane, 0.1f);
  EXPECT_GE(scene.camera.farPlane, 100000.0f);
}

TEST(DepthRangeScene, NearObjectIsVisibleInTheLowerLeftOfEveryFrame) {
  // The centre of the nearest world object (within 0.5 m) projects into the view's lower left at every path frame:
  // -0.98 <= ndc.x < 0, -0.98 <= ndc.y < 0 (y up), with a positive view depth.
  const Scene scene = makeBuiltInScene("depth-range");
  const Object* nearObject = nullptr;
  float nearest = std::numeric_limits<float>::max();
  for (const Object& o : scene.objects)
    if (o.layer == Layer::World)
      if (const float d = distanceToBox(worldBounds(scene, o), scene.camera.position); d < nearest) {
        nearest = d;
        nearObject = &o;
      }
  ASSERT_NE(nearObject, nullptr);
  ASSERT_LE(nearest, 0.5f);
  const Aabb box = worldBounds(scene, *nearObject);
  const glm::vec3 centre = 0.5f * (box.lo + box.hi);
  for (std::size_t f = 0; f < scene.cameraPath.size(); ++f) {
    const Camera& cam = scene.cameraPath[f];
    const glm::vec3 view = glm::transpose(cameraRotation(cam)) * (centre - cam.position);
    ASSERT_LT(view.z, 0.0f) << "frame " << f;
    const glm::vec4 clip = glm::perspective(cam.verticalFovRadians, kAspect, cam.nearPlane, cam.farPlane) *
                           glm::vec4(view, 1.0f);
    const glm::vec2 ndc(clip.x / clip.w, clip.y / clip.w);
    EXPECT_GE(ndc.x, -0.98f) << "frame " << f;
    EXPECT_LT(ndc.x, 0.0f) << "frame " << f;
    EXPECT_GE(ndc.y, -0.98f) << "frame " << f;
    EXPECT_LT(ndc.y, 0.0f) << "frame " << f;
  }
}

TEST(SceneCameraPaths, EachHasTwentyFourToFortyEightFrames) {
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    EXPECT_GE(scene.cameraPath.size(), 24u) << name;
    EXPECT_LE(scene.cameraPath.size(), 48u) << name;
  }
}

TEST(SceneCameraPaths, ConsecutiveFramesMoveLessThanHalfAMetre) {
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    for (std::size_t f = 1; f < scene.cameraPath.size(); ++f)
      EXPECT_LT(glm::distance(scene.cameraPath[f - 1].position, scene.cameraPath[f].position), 0.5f)
          << name << " frames " << f - 1 << "-" << f;
  }
}

TEST(SceneCameraPaths, ConsecutiveFramesTurnLessThanAHundredthOfATurn) {
  // |d yaw|, |d pitch| < 2 pi / 100 rad between neighbouring frames; lens and planes stay the same.
  for (const std::string& name : builtInSceneNames()) {
    const Scene scene = makeBuiltInScene(name);
    for (std::size_t f = 1; f < scene.cameraPath.size(); ++f) {
      const Camera& a = scene.cameraPath[f - 1];
      const Camera& b = scene.cameraPath[f];
      EXPECT_LT(std::abs(b.yawRadians - a.yawRadians), 0.0628f) << name << " frame " << f;
      EXPECT_LT(std::abs(b.pitchRadians - a.pitchRadians), 0.0628f) << name << " frame " << f;
      EXPECT_EQ(b.verticalFovRadians, a.verticalFovRadians) << name << " frame " << f;
      EXPECT_EQ(b.nearPlane, a.nearPlane) << name << " frame " << f;
      EXPECT_EQ(b.farPlane, a.farPlane) << name << " frame " << f;
    }
  }
}

TEST(SceneCameraForFrame, ReturnsEachFrameOfThePath) {
  const Scene scene = makeBuiltInScene("cover");
  ASSERT_FALSE(scene.cameraPath.empty());
  for (std::size_t f = 0; f < scene.cameraPath.size(); ++f)
    EXPECT_TRUE(sameCamera(cameraForFrame(scene, f), scene.cameraPath[f])) << "frame " << f;
}

TEST(SceneCameraForFrame, WithoutAPathFrameZeroIsTheCamera) {
  Scene scene = makeCourtyardScene();
  scene.cameraPath.clear();
  scene.camera.position = glm::vec3(1.0f, 2.0f, 3.0f);
  EXPECT_TRUE(sameCamera(cameraForFrame(scene, 0), scene.camera));
  EXPECT_THROW(cameraForFrame(scene, 1), std::out_of_range);
}

TEST(SceneCameraForFrame, ThrowsOutOfRangeNamingTheFrameAndTheCount) {
  const Scene scene = makeBuiltInScene("depth-range");
  const std::size_t count = scene.cameraPath.size();
  ASSERT_EQ(count, 48u);
  try {
    cameraForFrame(scene, 1000);
    FAIL() << "expected std::out_of_range";
  } catch (const std::out_of_range& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame 1000"), std::string::npos) << what;
    EXPECT_NE(what.find("48 frames"), std::string::npos) << what;
    EXPECT_NE(what.find("depth-range"), std::string::npos) << what;
  }
  EXPECT_THROW(cameraForFrame(scene, count), std::out_of_range);
  EXPECT_NO_THROW(cameraForFrame(scene, count - 1));
}

}  // namespace
}  // namespace s3d::renderer
