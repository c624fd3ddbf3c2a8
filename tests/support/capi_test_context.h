#pragma once
// The C API on a test's Vulkan device: the s3d_context a host binding C adopts, and its images as C structs.
#include <gtest/gtest.h>

#include "s3d/s3d.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"

namespace s3d::test {

class CContext {
 public:
  explicit CContext(vk::Context& context) {
    s3d_host_device device{};
    device.instance = context.instance();
    device.physical_device = context.physicalDevice();
    device.device = context.device();
    device.queue_family = context.queueFamily();
    device.queue = context.queue();
    EXPECT_EQ(s3d_context_create(&device, &context_), S3D_SUCCESS) << s3d_last_error();
  }
  ~CContext() { s3d_context_destroy(context_); }
  CContext(const CContext&) = delete;
  CContext& operator=(const CContext&) = delete;
  s3d_context get() const { return context_; }

 private:
  s3d_context context_ = nullptr;
};

// An image the test keeps in GENERAL and synchronizes itself (stage 0).
inline s3d_host_image cImage(const vk::Image& image) {
  return {image.image, image.view, image.format, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, 0};
}

}  // namespace s3d::test
