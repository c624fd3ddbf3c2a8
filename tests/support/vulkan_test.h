#pragma once
// Fixture for GPU tests: one Vulkan context with the Khronos validation layer on for the whole test binary;
// any validation message recorded during a test fails that test.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include "s3d/vk/context.h"

namespace s3d::test {

inline vk::Context& sharedVulkanContext() {
  static std::unique_ptr<vk::Context> context = [] {
    vk::ContextOptions options;
    options.validation = true;
    if (const char* device = std::getenv("S3D_TEST_DEVICE")) options.device = device;  // default: auto
    return std::make_unique<vk::Context>(options);
  }();
  return *context;
}

class VulkanTest : public ::testing::Test {
 protected:
  vk::Context& context() { return sharedVulkanContext(); }
  void SetUp() override { context().clearValidationMessages(); }
  void TearDown() override {
    for (const std::string& message : context().validationMessages()) ADD_FAILURE() << "validation: " << message;
    context().clearValidationMessages();
  }
};

}  // namespace s3d::test
