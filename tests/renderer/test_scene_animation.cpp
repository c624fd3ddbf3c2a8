// Skins and node animation (scene_animation.h, renderer/src/scene_pose.cpp, renderer/src/gltf_animation.cpp):
// glTF sampling by interpolation mode, the posed two-bone arm of skinned_arm.h against positions worked out by
// hand, looping, static scenes untouched, and the errors for bad skin and animation data.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "io_test_support.h"
#include "s3d/renderer/scene_animation.h"
#include "s3d/renderer/scene_file.h"
#include "skinned_arm.h"

namespace s3d::renderer {
namespace {
namespace fs = std::filesystem;

// Float rounding of a few multiplies and adds on values near 1: well under 1e-5.
constexpr float kTolerance = 1e-5f;

class ScratchFolder : public test::ScratchFolder {
 public:
  ScratchFolder() : test::ScratchFolder("s3d_anim_") {}
};

AnimationChannel channel(Interpolation interpolation, std::vector<float> times, std::vector<glm::vec4> values,
                         AnimatedProperty property = AnimatedProperty::Translation) {
  return {0, property, interpolation, std::move(times), std::move(values)};
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], kTolerance) << what << " component " << c;
}

TEST(SceneAnimation, LinearSamplingInterpolatesBetweenKeysAndHoldsTheEndsOutside) {
  const AnimationChannel c = channel(Interpolation::Linear, {1, 3}, {glm::vec4(0, 0, 0, 0), glm::vec4(4, 2, 0, 0)});
  EXPECT_EQ(sampleChannel(c, 1.0f), glm::vec4(0, 0, 0, 0));
  EXPECT_EQ(sampleChannel(c, 3.0f), glm::vec4(4, 2, 0, 0));
  EXPECT_EQ(sampleChannel(c, 1.5f), glm::vec4(1, 0.5f, 0, 0));  // a quarter of the way: exact in binary
  EXPECT_EQ(sampleChannel(c, 0.0f), glm::vec4(0, 0, 0, 0));    // before the first key
  EXPECT_EQ(sampleChannel(c, 9.0f), glm::vec4(4, 2, 0, 0));    // after the last
}

TEST(SceneAnimation, StepSamplingHoldsTheEarlierKeyUntilTheNext) {
  const AnimationChannel c = channel(Interpolation::Step, {0, 1, 2}, {glm::vec4(1), glm::vec4(2), glm::vec4(3)});
  EXPECT_EQ(sampleChannel(c, 0.0f), glm::vec4(1));
  EXPECT_EQ(sampleChannel(c, 0.999f), glm::vec4(1));
  EXPECT_EQ(sampleChannel(c, 1.0f), glm::vec4(2));
  EXPECT_EQ(sampleChannel(c, 1.5f), glm::vec4(2));
  EXPECT_EQ(sampleChannel(c, 2.0f), glm::vec4(3));
}

TEST(SceneAnimation, CubicSplineSamplingFollowsTheHermiteCurveWithTangentsScaledByTheInterval) {
  // Keys at 0 s and 2 s, both values 0, out-tangent 1 and in-tangent -1: y = 2 s (1 - s), s = t / 2.
  const AnimationChannel c = channel(Interpolation::CubicSpline, {0, 2},
                                     {glm::vec4(0), glm::vec4(0), glm::vec4(1), glm::vec4(-1), glm::vec4(0), glm::vec4(0)});
  EXPECT_EQ(sampleChannel(c, 0.0f).x, 0.0f);
  EXPECT_EQ(sampleChannel(c, 2.0f).x, 0.0f);
  EXPECT_NEAR(sampleChannel(c, 0.5f).x, 0.375f, kTolerance);  // s = 1/4
  EXPECT_NEAR(sampleChannel(c, 1.0f).x, 0.5f, kTolerance);    // s = 1/2, the top
}

TEST(SceneAnimation, LinearRotationIsTheSlerpAlongTheShorterArc) {
  const float h = std::sqrt(0.5f);
  // 0 to 90 degrees about +Z, the second key stored as its negative (the same rotation the long way round).
  const AnimationChannel c = channel(Interpolation::Linear, {0, 1}, {glm::vec4(0, 0, 0, 1), glm::vec4(0, 0, -h, -h)},
                                     AnimatedProperty::Rotation);
  const glm::vec4 half = sampleChannel(c, 0.5f);
  const float angle = 2.0f * std::acos(std::abs(half.w));
  EXPECT_NEAR(angle, glm::radians(45.0f), kTolerance);
  EXPECT_NEAR(glm::length(half), 1.0f, kTolerance);  // slerp keeps unit length (a plain lerp would not)
}

TEST(SceneAnimation, TheArmLoadsItsSkinWeightsAndFirstAnimation) {
  ScratchFolder folder;
  const Scene scene = loadGltfScene(test::SkinnedArm().write(folder.path()));
  ASSERT_TRUE(scene.animation);
  const SceneAnimation& a = *scene.animation;
  EXPECT_EQ(a.animationName, "wave");
  EXPECT_EQ(a.channels.size(), 3u);
  EXPECT_EQ(a.duration(), 2.0);
  ASSERT_EQ(a.skins.size(), 1u);
  EXPECT_EQ(a.skins[0].joints, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(a.skins[0].inverseBindMatrices[1][3], glm::vec4(-1, 0, 0, 1));
  ASSERT_EQ(a.skinnedMeshes.size(), 1u);
  EXPECT_EQ(a.skinnedMeshes[0].weights[2][0], 0.5f);
  EXPECT_EQ(a.nodes[2].parent, 1);
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].transform, glm::mat4(1.0f));  // skinned: placed by its joints
}

// At 0.5 s: the elbow turned 45 degrees about +Z, the shoulder lifted by y(0.25) = 0.375, scale still 1.
TEST(SceneAnimation, ThePosedArmsVerticesAreWhereTheJointsPutThem) {
  ScratchFolder folder;
  Scene scene = loadGltfScene(test::SkinnedArm().write(folder.path()));
  poseScene(scene, 0.5);
  const float c = std::sqrt(0.5f), lift = 0.375f;
  const std::vector<Vertex>& v = scene.meshes[0].vertices;
  expectNear(v[0].position, {0, lift - 0.1f, 0}, "shoulder vertex (0, -0.1)");
  expectNear(v[5].position, {1 + 0.9f * c, lift + 1.1f * c, 0}, "elbow vertex (2, 0.1)");
  expectNear(v[4].position, {1 + 1.1f * c, lift + 0.9f * c, 0}, "elbow vertex (2, -0.1)");
  // Half shoulder (1, 0.1), half elbow (1 - 0.1 c, 0.1 c), both lifted.
  expectNear(v[3].position, {0.5f * (1 + 1 - 0.1f * c), lift + 0.5f * (0.1f + 0.1f * c), 0}, "blended vertex (1, 0.1)");
  expectNear(v[5].normal, {0, 0, 1}, "normal turned about its own axis");
}

TEST(SceneAnimation, AtTheFirstKeysTheArmIsAtRestAndTheStepScaleAppliesFromItsKey) {
  ScratchFolder folder;
  Scene scene = loadGltfScene(test::SkinnedArm().write(folder.path()));  // posed at 0 s by the loader
  expectNear(scene.meshes[0].vertices[5].position, {2, 0.1f, 0}, "rest");
  poseScene(scene, 1.5);  // elbow 45 degrees back from 90, lift y(0.75) = 0.375, scale 0.5 about the shoulder
  const float c = std::sqrt(0.5f);
  expectNear(scene.meshes[0].vertices[5].position, {0.5f * (1 + 0.9f * c), 0.375f + 0.5f * 1.1f * c, 0}, "scaled");
}

TEST(SceneAnimation, TimeLoopsOverTheAnimationsDuration) {
  ScratchFolder folder;
  Scene early = loadGltfScene(test::SkinnedArm().write(folder.path()));
  Scene late = early;
  poseScene(early, 0.5);
  poseScene(late, 2.5);  // duration 2 s
  for (std::size_t i = 0; i < early.meshes[0].vertices.size(); ++i)
    expectNear(late.meshes[0].vertices[i].position, early.meshes[0].vertices[i].position, "vertex " + std::to_string(i));
}

TEST(SceneAnimation, AStaticSceneHasNoAnimationAndPosingLeavesItAlone) {
  Scene scene = makeBuiltInScene("courtyard");
  EXPECT_FALSE(scene.animation);
  const glm::mat4 before = scene.objects[0].transform;
  poseScene(scene, 3.0);
  EXPECT_EQ(scene.objects[0].transform, before);
  EXPECT_FALSE(loadGltfScene(fs::path(S3D_TEST_DATA_DIR) / "textured_quad.gltf").animation);
}

// The glTF tutorial's simple skin (Debian's assimp-testmodels): two joints, the upper one rotating.
TEST(SceneAnimation, TheGltfTutorialsSimpleSkinPosesItsUpperHalf) {
  const fs::path file = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
  if (!fs::exists(file)) GTEST_SKIP() << file << " is absent (Debian package assimp-testmodels)";
  Scene scene = loadGltfScene(file);
  ASSERT_TRUE(scene.animation);
  const std::vector<Vertex> rest = scene.meshes[0].vertices;
  poseScene(scene, 1.5);  // the second joint's rotation is near its largest (keys 0.5 .. 5.5 s)
  float bottomMoved = 0.0f, topMoved = 0.0f;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const float moved = glm::length(scene.meshes[0].vertices[i].position - rest[i].position);
    ASSERT_TRUE(std::isfinite(moved)) << "vertex " << i;
    float& largest = rest[i].position.y < 0.25f ? bottomMoved : topMoved;
    largest = std::max(largest, moved);
  }
  EXPECT_EQ(bottomMoved, 0.0f);  // weighted to the unmoving root joint only
  EXPECT_GT(topMoved, 0.1f);     // the top of the 2-unit strip swings visibly
}

// What loading the arm written into `folder` throws as E ("" when it loads or throws something else).
template <typename E>
std::string errorOfLoading(const test::SkinnedArm& arm, const fs::path& folder) {
  const fs::path file = arm.write(folder);
  return test::errorOf<E>([&] { (void)loadGltfScene(file); });
}

TEST(SceneAnimation, AJointIndexPastTheSkinsJointsIsNamed) {
  ScratchFolder folder;
  test::SkinnedArm arm;
  arm.joints[4 * 3] = 7;
  const std::string error = errorOfLoading<std::runtime_error>(arm, folder.path());
  EXPECT_NE(error.find("arm.gltf"), std::string::npos) << error;
  EXPECT_NE(error.find("mesh 0 primitive 0's JOINTS_0 names joint 7 at vertex 3, but skin 0 has 2 joints"),
            std::string::npos) << error;
}

TEST(SceneAnimation, ANonFiniteWeightIsNamed) {
  ScratchFolder folder;
  test::SkinnedArm arm;
  arm.weights[4 * 2 + 1] = std::numeric_limits<float>::quiet_NaN();
  const std::string error = errorOfLoading<std::runtime_error>(arm, folder.path());
  EXPECT_NE(error.find("arm.gltf"), std::string::npos) << error;
  EXPECT_NE(error.find("mesh 0 primitive 0's WEIGHTS_0 contains a non-finite value"), std::string::npos) << error;
}

TEST(SceneAnimation, AVertexNoJointWeighsFollowsItsMeshNode) {
  // Exporters leave vertices bound to no joint (all weights 0; a Blender level's lever does): they stay where the
  // mesh's own node puts them, here the unanimated identity, instead of collapsing to the origin.
  ScratchFolder folder;
  test::SkinnedArm arm;
  for (int i = 0; i < 4; ++i) arm.weights[4 * 5 + i] = 0.0f;
  Scene scene = loadGltfScene(arm.write(folder.path()));
  poseScene(scene, 0.5);
  expectNear(scene.meshes[0].vertices[5].position, {2, 0.1f, 0}, "unweighted elbow vertex (2, 0.1) at rest");
}

TEST(SceneAnimation, InverseBindMatricesOfTheWrongCountAreNamed) {
  ScratchFolder folder;
  test::SkinnedArm arm;
  arm.inverseBindMatrices.resize(16 * 3, 0.0f);
  const std::string error = errorOfLoading<std::runtime_error>(arm, folder.path());
  EXPECT_NE(error.find("skin 0 ('arm skin')'s inverseBindMatrices hold 3 matrices for its 2 joints"),
            std::string::npos) << error;
}

TEST(SceneAnimation, SamplerKeyTimesThatDoNotIncreaseAreNamed) {
  ScratchFolder folder;
  test::SkinnedArm arm;
  arm.rotationTimes = {0, 1, 1};
  const std::string error = errorOfLoading<std::runtime_error>(arm, folder.path());
  EXPECT_NE(error.find("arm.gltf"), std::string::npos) << error;
  EXPECT_NE(error.find("animation 0 ('wave') sampler 0's input times do not increase at key 2"), std::string::npos)
      << error;
}

}  // namespace
}  // namespace s3d::renderer
