#pragma once
// The Vulkan context every benchmark of this folder times on: the device S3D_BENCH_DEVICE names (auto when unset),
// created once per process.
#include <cstdlib>
#include <memory>

#include "s3d/vk/context.h"

namespace s3d::bench {

inline vk::Context& benchContext() {
  static std::unique_ptr<vk::Context> context = [] {
    vk::ContextOptions options;
    if (const char* device = std::getenv("S3D_BENCH_DEVICE")) options.device = device;
    return std::make_unique<vk::Context>(options);
  }();
  return *context;
}

}  // namespace s3d::bench
