#include "s3d/stereo/hybrid_pass.h"

#include <cstring>
#include <stdexcept>

// clang-format off
#include <s3d_spirv/stereo_hybrid_classify_comp.h>
#include <s3d_spirv/stereo_hybrid_composite_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

constexpr VkFormat kBinFormat = VK_FORMAT_R32_UINT;
constexpr vk::ImageState kCleared{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                  VK_ACCESS_2_TRANSFER_WRITE_BIT};
// The histogram's atomics read and write it.
constexpr vk::ImageState kAtomics{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};

vk::PipelineLayout storageImageLayout(const vk::Context& context, std::uint32_t count) {
  VkDescriptorSetLayoutBinding bindings[4];
  for (std::uint32_t i = 0; i < count; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  return vk::createPushDescriptorLayout(context, std::span(bindings, count), sizeof(gpu::HybridConstants),
                                        VK_SHADER_STAGE_COMPUTE_BIT);
}

void requireSize(const vk::Image& image, const gpu::HybridConstants& c, const char* what) {
  if (int(image.width) != c.width || int(image.height) != c.height)
    throw std::invalid_argument(std::string("HybridPass: ") + what + " size does not match the constants");
}

std::uint32_t groups(int size) { return std::uint32_t((size + S3D_HYBRID_GROUP_SIZE - 1) / S3D_HYBRID_GROUP_SIZE); }

}  // namespace

HybridPass::HybridPass(const vk::Context& context)
    : context_(&context), classifyLayout_(storageImageLayout(context, 4)), compositeLayout_(storageImageLayout(context, 3)) {
  classify_ = vk::createComputePipeline(context, classifyLayout_.layout, spirv_stereo_hybrid_classify_comp);
  composite_ = vk::createComputePipeline(context, compositeLayout_.layout, spirv_stereo_hybrid_composite_comp);
}

HybridPass::Classification HybridPass::createClassification(std::uint32_t width, std::uint32_t height) const {
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  return {vk::createImage(*context_, kBinFormat, width, height, usage),
          vk::createImage(*context_, kBinFormat, width, height, usage),
          vk::createImage(*context_, kBinFormat, S3D_HYBRID_BINS, 2, usage)};
}

void HybridPass::recordClassify(VkCommandBuffer cmd, const vk::Image& linearDepth, const Classification& target,
                                bool fresh, const gpu::HybridConstants& c) const {
  requireSize(linearDepth, c, "linear depth");
  requireSize(target.leftBins, c, "left bins");
  requireSize(target.rightBins, c, "right bins");
  const vk::ImageState previous = fresh ? vk::kUndefined : vk::kComputeWrite;
  vk::transition(cmd, target.leftBins, previous, vk::kComputeWrite);
  vk::transition(cmd, target.rightBins, previous, vk::kComputeWrite);
  vk::transition(cmd, target.histogram, previous, kCleared);
  const VkClearColorValue zero{};
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, target.histogram.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
  vk::transition(cmd, target.histogram, kCleared, kAtomics);

  VkDescriptorImageInfo infos[4] = {{VK_NULL_HANDLE, linearDepth.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, target.leftBins.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, target.rightBins.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, target.histogram.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[4];
  for (std::uint32_t i = 0; i < 4; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classify_.get());
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, classifyLayout_.layout, 0, 4, writes);
  vkCmdPushConstants(cmd, classifyLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  vkCmdDispatch(cmd, groups(c.width), groups(c.height), 1);
  vk::transition(cmd, target.histogram, kAtomics, vk::kComputeWrite);
}

void HybridPass::recordComposite(VkCommandBuffer cmd, const vk::Image& eye, const vk::Image& renderedEye,
                                 const vk::Image& bins, const gpu::HybridConstants& c) const {
  requireSize(eye, c, "eye");
  requireSize(renderedEye, c, "rendered eye");
  requireSize(bins, c, "bins");
  VkDescriptorImageInfo infos[3] = {{VK_NULL_HANDLE, eye.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, renderedEye.view, VK_IMAGE_LAYOUT_GENERAL},
                                    {VK_NULL_HANDLE, bins.view, VK_IMAGE_LAYOUT_GENERAL}};
  VkWriteDescriptorSet writes[3];
  for (std::uint32_t i = 0; i < 3; ++i) writes[i] = vk::storageImageWrite(i, &infos[i]);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, composite_.get());
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, compositeLayout_.layout, 0, 3, writes);
  vkCmdPushConstants(cmd, compositeLayout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  vkCmdDispatch(cmd, groups(c.width), groups(c.height), 1);
}

HybridHistogram HybridPass::readHistogram(vk::Context& context, const vk::Image& histogram, int row) {
  const std::vector<std::byte> bytes = vk::readbackImage(context, histogram, vk::kComputeWrite);
  std::uint32_t counts[S3D_HYBRID_BINS];
  std::memcpy(counts, bytes.data() + std::size_t(row) * sizeof(counts), sizeof(counts));
  HybridHistogram result{};
  for (std::size_t i = 0; i < result.size(); ++i) result[i] = counts[i];
  return result;
}

std::vector<std::uint32_t> HybridPass::readBins(vk::Context& context, const vk::Image& bins) {
  const std::vector<std::byte> bytes = vk::readbackImage(context, bins, vk::kComputeWrite);
  std::vector<std::uint32_t> result(bytes.size() / sizeof(std::uint32_t));
  std::memcpy(result.data(), bytes.data(), bytes.size());
  return result;
}

HybridClassification classifyHybridOnGpu(vk::Context& context, const DepthImage& linearDepth,
                                         const gpu::HybridConstants& constants) {
  const HybridPass pass(context);
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  const vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, linearDepth.width, linearDepth.height, usage);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeRead);
  const HybridPass::Classification target = pass.createClassification(linearDepth.width, linearDepth.height);
  context.submitAndWait([&](VkCommandBuffer cmd) { pass.recordClassify(cmd, depth, target, true, constants); });
  return {HybridPass::readBins(context, target.leftBins), HybridPass::readBins(context, target.rightBins),
          HybridPass::readHistogram(context, target.histogram, 0), HybridPass::readHistogram(context, target.histogram, 1)};
}

ImageRGBA8 compositeHybridOnGpu(vk::Context& context, const ImageRGBA8& eye, const ImageRGBA8& rendered,
                                const std::vector<std::uint32_t>& bins, const gpu::HybridConstants& constants) {
  requireSameSize(eye, rendered, "hybrid composite (eye vs rendered eye)");
  const HybridPass pass(context);
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  auto image = [&](VkFormat format) { return vk::createImage(context, format, eye.width, eye.height, usage); };
  const vk::Image eyeImage = image(VK_FORMAT_R8G8B8A8_UNORM), renderedImage = image(VK_FORMAT_R8G8B8A8_UNORM),
                  binImage = image(kBinFormat);
  vk::uploadImage(context, eyeImage, std::as_bytes(std::span(eye.pixels)), vk::kComputeWrite);
  vk::uploadImage(context, renderedImage, std::as_bytes(std::span(rendered.pixels)), vk::kComputeRead);
  vk::uploadImage(context, binImage, std::as_bytes(std::span(bins)), vk::kComputeRead);
  context.submitAndWait([&](VkCommandBuffer cmd) { pass.recordComposite(cmd, eyeImage, renderedImage, binImage, constants); });
  ImageRGBA8 result(eye.width, eye.height);
  const std::vector<std::byte> bytes = vk::readbackImage(context, eyeImage, vk::kComputeWrite);
  std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
  return result;
}

}  // namespace s3d::stereo
