// Listing 4.3: device depth back to linear depth, for the world and for the first-person layer.
#include <gtest/gtest.h>

#include <cmath>

#include "s3d/gpu/linear_depth.h"

namespace s3d::gpu {
namespace {

// Device depth a zero-to-one projection (near n, far f) writes for linear depth d, in viewport range [a, b].
float deviceDepthOf(double d, double n, double f, double a, double b) {
  double ndcZ = f / (f - n) - f * n / ((f - n) * d);
  return float(a + ndcZ * (b - a));
}

constexpr float kWorldNear = 0.1f, kWorldFar = 1000.0f, kWeaponNear = 0.02f, kWeaponFar = 4.0f, kSplit = 0.1f;

TEST(LinearDepth, WorldDepthIsReconstructed) {
  LinearDepthParams p = makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  // Relative tolerance 1e-3: one float ulp of device depth near 1 (6e-8) is d/near * 6e-8 relative at depth d.
  // From just beyond the near plane: exactly at it the device depth equals the split and reads as first-person.
  for (double d : {0.1001, 0.5, 2.0, 10.0, 100.0, 900.0})
    EXPECT_NEAR(linearDepthFromDevice(p, deviceDepthOf(d, kWorldNear, kWorldFar, kSplit, 1.0)), d, d * 2e-3) << d;
}

TEST(LinearDepth, FirstPersonDepthUsesItsOwnRange) {
  LinearDepthParams p = makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  // Relative tolerance 1e-4: the first-person range [0, 0.1] keeps float precision high.
  for (double d : {0.02, 0.1, 0.3, 0.6, 3.9}) {
    float device = deviceDepthOf(d, kWeaponNear, kWeaponFar, 0.0, kSplit);
    ASSERT_LE(device, kSplit);
    EXPECT_NEAR(linearDepthFromDevice(p, device), d, d * 1e-4) << d;
  }
}

TEST(LinearDepth, TheWeaponAndTheWorldAtTheSameDeviceDepthDiffer) {
  // The two ranges only meet at the split; just above it the world's near plane, just below the weapon's far.
  LinearDepthParams p = makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  EXPECT_NEAR(linearDepthFromDevice(p, kSplit), kWeaponFar, 1e-3);
  EXPECT_NEAR(linearDepthFromDevice(p, std::nextafter(kSplit, 1.0f)), kWorldNear, 1e-3);
}

TEST(LinearDepth, TheClearedFarPlaneIsSkyAtInfiniteDistance) {
  LinearDepthParams p = makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  EXPECT_TRUE(std::isinf(linearDepthFromDevice(p, 1.0f)));
  EXPECT_GT(linearDepthFromDevice(p, 1.0f), 0.0f);
}

}  // namespace
}  // namespace s3d::gpu

namespace s3d::gpu {
namespace {

TEST(StereoDepth, PushesOnlyTheFirstPersonLayer) {
  // Seed 4.6.2: pushed = offset + scale * depth for the weapon; the world keeps its depth. Tolerances as above.
  LinearDepthParams p = makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  p.firstPersonDepthOffset = 1.0f;
  p.firstPersonDepthScale = 2.0f;
  float weapon = deviceDepthOf(0.4, kWeaponNear, kWeaponFar, 0.0, kSplit);
  EXPECT_NEAR(stereoDepthFromDevice(p, weapon), 1.0f + 2.0f * 0.4f, 1e-4f);
  float world = deviceDepthOf(10.0, kWorldNear, kWorldFar, kSplit, 1.0);
  EXPECT_NEAR(stereoDepthFromDevice(p, world), 10.0f, 2e-2f);
  EXPECT_TRUE(std::isinf(stereoDepthFromDevice(p, 1.0f)));
}

TEST(StereoDepth, DepthNearerThanTheRangeAndNaNAreNoSurface) {
  // 0 (the stereo pass's zero-parallax plane) below the near end; beyond the far end stays sky, in both conventions.
  const LinearDepthParams p = makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  const LinearDepthParams reversed = makeReversedLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit);
  EXPECT_EQ(stereoDepthFromDevice(p, -0.25f), 0.0f);
  EXPECT_EQ(stereoDepthFromDevice(p, std::nanf("")), 0.0f);
  EXPECT_TRUE(std::isinf(stereoDepthFromDevice(p, 1.5f)));
  EXPECT_EQ(stereoDepthFromDevice(reversed, 1.25f), 0.0f);
  EXPECT_EQ(stereoDepthFromDevice(reversed, std::nanf("")), 0.0f);
  EXPECT_TRUE(std::isinf(stereoDepthFromDevice(reversed, -0.5f)));
}

TEST(StereoDepth, NeverDecreasesWithTheKeyWithoutAFirstPersonLayer) {
  // What lets the host gather take its taps' minimum in device depth: with no first-person range (split 0), the
  // stereo depth never decreases as deviceDepthKey grows, from the near end through the sky, in both conventions.
  for (bool isReversed : {false, true}) {
    LinearDepthParams p = isReversed ? makeReversedLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, 0.0f)
                                     : makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, 0.0f);
    p.firstPersonDeviceDepthMax = -1.0f;  // as stereo::linearDepthParams sets it for no first-person range
    ASSERT_TRUE(hasNoFirstPersonLayer(p));
    float previousKey = -2.0f, previousDepth = 0.0f;
    for (int i = 0; i <= 1 << 14; ++i) {
      const float device = isReversed ? 1.0f - float(i) / float(1 << 14) : float(i) / float(1 << 14);
      const float key = deviceDepthKey(p, device);
      ASSERT_GT(key, previousKey);
      const float depth = stereoDepthFromDevice(p, device);
      EXPECT_GE(depth, previousDepth) << device << (isReversed ? " reversed" : "");
      previousKey = key;
      previousDepth = depth;
    }
  }
}

TEST(StereoDepth, AFirstPersonRangeIsALayer) {
  EXPECT_FALSE(hasNoFirstPersonLayer(makeLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit)));
  EXPECT_FALSE(hasNoFirstPersonLayer(makeReversedLinearDepthParams(kWorldNear, kWorldFar, kWeaponNear, kWeaponFar, kSplit)));
}

}  // namespace
}  // namespace s3d::gpu
