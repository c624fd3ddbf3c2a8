// The ray-cast pass's view work recorded ahead (RaycastVisibility::recordPreparation): a prepared view casts what
// an unprepared one casts, a record for another camera sets up its own, and steps out of order are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/renderer/raycast_visibility.h"
#include "s3d/renderer/scene_bvh.h"
#include "vulkan_test.h"

namespace s3d {
namespace {

using renderer::RaycastCamera;
using Step = renderer::RaycastVisibility::PreparationStep;

constexpr std::uint32_t kWidth = 96, kHeight = 54;

class RaycastPreparation : public test::VulkanTest {
 protected:
  RaycastPreparation()
      : scene_(renderer::makeBuiltInScene("courtyard")), bvh_(renderer::SceneBvh::build(scene_)), pass_(context()) {
    pass_.setBvh(bvh_);
    pass_.setSearch(renderer::RaycastSearch::Bins);  // every step has work: setup, bins and the large triangles
  }

  RaycastCamera camera(float eyeOffset) const {
    renderer::ViewMatrices view = renderer::centerViewMatrices(scene_, float(kWidth) / kHeight);
    view.worldView = glm::translate(glm::mat4(1.0f), glm::vec3(-eyeOffset, 0.0f, 0.0f)) * view.worldView;
    return renderer::raycastCamera(scene_, view);
  }

  // The three steps in one submission, ordered by compute barriers as the caller must.
  void prepare(const RaycastCamera& view) {
    context().submitAndWait([&](VkCommandBuffer cmd) {
      for (const Step step : {Step::Setup, Step::Bins, Step::LargeBins}) {
        vk::computeStorageBarrier(cmd);
        pass_.recordPreparation(cmd, step, view, kWidth, kHeight);
      }
    });
  }

  // Every pixel's id and device depth bits from one recording of the pass.
  std::vector<std::uint32_t> cast(const RaycastCamera& view) {
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const vk::Image ids = vk::createImage(context(), VK_FORMAT_R32_UINT, kWidth, kHeight, usage);
    const vk::Image depth = vk::createImage(context(), VK_FORMAT_R32_SFLOAT, kWidth, kHeight, usage);
    context().submitAndWait([&](VkCommandBuffer cmd) {
      vk::transition(cmd, ids, vk::kUndefined, vk::kComputeWrite);
      vk::transition(cmd, depth, vk::kUndefined, vk::kComputeWrite);
      pass_.record(cmd, view, renderer::ShadeMask{}, ids, depth);
    });
    std::vector<std::uint32_t> words(2 * std::size_t(kWidth) * kHeight);
    const std::vector<std::byte> idBytes = vk::readbackImage(context(), ids, vk::kComputeWrite);
    const std::vector<std::byte> depthBytes = vk::readbackImage(context(), depth, vk::kComputeWrite);
    std::memcpy(words.data(), idBytes.data(), idBytes.size());
    std::memcpy(words.data() + words.size() / 2, depthBytes.data(), depthBytes.size());
    return words;
  }

  renderer::Scene scene_;
  renderer::SceneBvh bvh_;
  renderer::RaycastVisibility pass_;
};

// Prepared ahead, the record casts from the prepared setup and bins (it skips its own) and finds the same ids and
// depths, bit for bit, as a record that sets up for itself; the preparation serves that one record.
TEST_F(RaycastPreparation, APreparedViewCastsWhatAnUnpreparedOneCasts) {
  const RaycastCamera left = camera(-0.03f), right = camera(0.03f);
  const std::vector<std::uint32_t> expected = cast(left);
  (void)cast(right);  // the buffers hold another view's setup
  prepare(left);
  ASSERT_TRUE(pass_.isPrepared(left, kWidth, kHeight));
  EXPECT_EQ(cast(left), expected);
  EXPECT_FALSE(pass_.isPrepared(left, kWidth, kHeight));
}

// A record for a camera other than the one prepared sets up its own view: the other camera's pixels, exactly.
TEST_F(RaycastPreparation, ARecordForAnotherCameraSetsUpItsOwn) {
  const RaycastCamera left = camera(-0.03f), right = camera(0.03f);
  const std::vector<std::uint32_t> expected = cast(right);
  prepare(left);
  EXPECT_FALSE(pass_.isPrepared(right, kWidth, kHeight));
  EXPECT_FALSE(pass_.isPrepared(left, kWidth, kHeight / 2));
  EXPECT_EQ(cast(right), expected);
  EXPECT_NE(cast(left), expected);  // the two views differ, so the check above could fail
}

// Bins before their setup, or the large triangles after another camera's setup, are refused; a new tree drops a
// prepared view (its triangles are not the tree's).
TEST_F(RaycastPreparation, StepsOutOfOrderAreRefused) {
  const RaycastCamera left = camera(-0.03f), right = camera(0.03f);
  context().submitAndWait([&](VkCommandBuffer cmd) {
    EXPECT_THROW(pass_.recordPreparation(cmd, Step::Bins, left, kWidth, kHeight), std::logic_error);
    pass_.recordPreparation(cmd, Step::Setup, left, kWidth, kHeight);
    vk::computeStorageBarrier(cmd);
    EXPECT_THROW(pass_.recordPreparation(cmd, Step::LargeBins, right, kWidth, kHeight), std::logic_error);
  });
  prepare(left);
  pass_.setBvh(bvh_);
  EXPECT_FALSE(pass_.isPrepared(left, kWidth, kHeight));
}

}  // namespace
}  // namespace s3d
