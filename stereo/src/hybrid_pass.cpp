#include "s3d/stereo/hybrid_pass.h"

#include <cstring>
#include <stdexcept>
#include <string>

// clang-format off
#include <s3d_spirv/stereo_hybrid_grid_depth_comp.h>
#include <s3d_spirv/stereo_hybrid_classify_comp.h>
#include <s3d_spirv/stereo_hybrid_threshold_comp.h>
#include <s3d_spirv/stereo_hybrid_mask_comp.h>
#include <s3d_spirv/stereo_hybrid_composite_comp.h>
#include <s3d_spirv/stereo_hybrid_crop_edges_comp.h>
// clang-format on

namespace s3d::stereo {
namespace {

// The fallback shape fits what every Vulkan device has (16 KiB of shared memory, 128 invocations).
static_assert(S3D_HYBRID_CLASSIFY_SHARED_BYTES(S3D_HYBRID_ROW_GROUP, 2 * S3D_HYBRID_CHUNK) <= 16384);
static_assert(S3D_HYBRID_ROW_GROUP <= 128);

constexpr VkFormat kUintFormat = VK_FORMAT_R32_UINT;
constexpr vk::ImageState kCleared{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                  VK_ACCESS_2_TRANSFER_WRITE_BIT};
// The histogram's atomics read and write it.
constexpr vk::ImageState kAtomics{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
// A later frame's writes wait for whatever read the images last (the renderer reads the masks in any stage).
constexpr vk::ImageState kReadAnywhere{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};

vk::PipelineLayout storageImageLayout(const vk::Context& context, std::uint32_t count) {
  VkDescriptorSetLayoutBinding bindings[6];
  for (std::uint32_t i = 0; i < count; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  return vk::createPushDescriptorLayout(context, std::span(bindings, count), sizeof(gpu::HybridConstants),
                                        VK_SHADER_STAGE_COMPUTE_BIT);
}

void requireSize(const vk::Image& image, const gpu::HybridConstants& c, const char* what) {
  if (int(image.width) != c.width || int(image.height) != c.height)
    throw std::invalid_argument(std::string("hybrid stereo: the ") + what + " size does not match the constants");
}

std::uint32_t groups(int size) { return std::uint32_t((size + S3D_HYBRID_GROUP_SIZE - 1) / S3D_HYBRID_GROUP_SIZE); }

// Binds `images` (storage, GENERAL) in order and dispatches.
void dispatch(const vk::Context& context, VkCommandBuffer cmd, VkPipeline pipeline, VkPipelineLayout layout,
              std::initializer_list<const vk::Image*> images, const gpu::HybridConstants& c, std::uint32_t groupsX,
              std::uint32_t groupsY) {
  VkDescriptorImageInfo infos[6];
  VkWriteDescriptorSet writes[6];
  std::uint32_t count = 0;
  for (const vk::Image* image : images) {
    infos[count] = {VK_NULL_HANDLE, image->view, VK_IMAGE_LAYOUT_GENERAL};
    writes[count] = vk::storageImageWrite(count, &infos[count]);
    ++count;
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  context.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, count, writes);
  vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(c), &c);
  vkCmdDispatch(cmd, groupsX, groupsY, 1);
}

std::vector<std::uint32_t> readUints(vk::Context& context, const vk::Image& image) {
  const std::vector<std::byte> bytes = vk::readbackImage(context, image, vk::kComputeWrite);
  std::vector<std::uint32_t> result(bytes.size() / sizeof(std::uint32_t));
  std::memcpy(result.data(), bytes.data(), bytes.size());
  return result;
}

HybridRowShape checkedShape(const vk::Context& context, std::optional<HybridRowShape> shape) {
  const HybridRowShape chosen = shape.value_or(hybridRowShapeFor(context));
  if (!hybridRowShapeFits(context, chosen))
    throw std::invalid_argument("hybrid stereo: the device cannot run a row group of " + std::to_string(chosen.rowGroup) +
                                " invocations (an even count where they share slots) with a chunk of " +
                                std::to_string(chosen.chunk) + " pixels, or mask runs of " +
                                std::to_string(chosen.maskRun) + " cells");
  return chosen;
}

}  // namespace

bool hybridRowShapeFits(const vk::Context& context, HybridRowShape shape) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  const VkPhysicalDeviceLimits& limits = properties.limits;
  auto groupFits = [&](int group) {
    return group > 0 && std::uint32_t(group) <= limits.maxComputeWorkGroupInvocations &&
           std::uint32_t(group) <= limits.maxComputeWorkGroupSize[0];
  };
  // Independent runs keep the chunk's slots in private memory (one shared slot each), split evenly by the group;
  // shared slots hold both eyes' chunks, each eye classified by half the group.
  const std::uint64_t sharedSlots = shape.independentRuns ? 1 : 2 * std::uint64_t(shape.chunk);
  return groupFits(shape.rowGroup) && shape.chunk > 0 && shape.maskRun > 0 &&
         (shape.independentRuns ? shape.chunk % shape.rowGroup == 0 : shape.rowGroup % 2 == 0) &&
         std::uint64_t(S3D_HYBRID_CLASSIFY_SHARED_BYTES(std::uint64_t(shape.rowGroup), sharedSlots)) <=
             limits.maxComputeSharedMemorySize;
}

HybridRowShape hybridRowShapeFor(const vk::Context& context) {
  if (context.isCpuDevice() && hybridRowShapeFits(context, kHybridCpuRowShape)) return kHybridCpuRowShape;
  if (!context.isCpuDevice() && hybridRowShapeFits(context, kHybridGpuRowShape)) return kHybridGpuRowShape;
  return kHybridFallbackRowShape;
}

HybridPass::HybridPass(const vk::Context& context, std::optional<HybridRowShape> shape)
    : context_(&context),
      shape_(checkedShape(context, shape)),
      gridDepthLayout_(storageImageLayout(context, 3)),
      classifyLayout_(storageImageLayout(context, 5)),
      thresholdLayout_(storageImageLayout(context, 5)),
      maskLayout_(storageImageLayout(context, 5)),
      compositeLayout_(storageImageLayout(context, 3)),
      cropEdgesLayout_(storageImageLayout(context, 1)),
      // Specialization: constant 0 the row group (also the workgroup size), 1 the classification's chunk, 2
      // whether the invocations classify independent runs (a 32-bit VkBool32), 3 the base's tap capacity.
      classify_(context, classifyLayout_.layout, spirv_stereo_hybrid_classify_comp,
                {std::uint32_t(shape_.rowGroup), std::uint32_t(shape_.chunk),
                 shape_.independentRuns ? VK_TRUE : VK_FALSE}) {
  gridDepth_ = vk::createComputePipeline(context, gridDepthLayout_.layout, spirv_stereo_hybrid_grid_depth_comp);
  threshold_ = vk::createComputePipeline(context, thresholdLayout_.layout, spirv_stereo_hybrid_threshold_comp);
  mask_ = vk::createComputePipeline(context, maskLayout_.layout, spirv_stereo_hybrid_mask_comp,
                                    vk::SpecializationWords({std::uint32_t(shape_.maskRun)}));
  composite_ = vk::createComputePipeline(context, compositeLayout_.layout, spirv_stereo_hybrid_composite_comp);
  cropEdges_ = vk::createComputePipeline(context, cropEdgesLayout_.layout, spirv_stereo_hybrid_crop_edges_comp);
}

HybridPass::Images HybridPass::createImages(std::uint32_t width, std::uint32_t height, int cell) const {
  if (cell < 1) throw std::invalid_argument("hybrid stereo: the classification's cell must be at least one pixel");
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  auto image = [&](std::uint32_t w, std::uint32_t h) { return vk::createImage(*context_, kUintFormat, w, h, usage); };
  const auto gridWidth = std::uint32_t(gpu::hybridGridSize(int(width), cell));
  const auto gridHeight = std::uint32_t(gpu::hybridGridSize(int(height), cell));
  Images images;
  images.cell = cell;
  if (cell > 1) images.gridDepth = vk::createImage(*context_, VK_FORMAT_R32_SFLOAT, gridWidth, gridHeight, usage);
  images.leftBins = image(gridWidth, gridHeight);
  images.rightBins = image(gridWidth, gridHeight);
  images.histogram = image(S3D_HYBRID_BINS, 2);
  images.rowHistograms = image(2 * S3D_HYBRID_BINS, gridHeight);
  images.thresholds = image(S3D_HYBRID_THRESHOLD_FIELDS, 2);
  images.leftMask = image(width, height);
  images.rightMask = image(width, height);
  return images;
}

void HybridPass::recordMasks(VkCommandBuffer cmd, const vk::Image& linearDepth, Images& images,
                             const gpu::HybridConstants& c, const std::function<void()>& afterEachDispatch) const {
  auto mark = [&] {
    if (afterEachDispatch) afterEachDispatch();
  };
  if (c.cell != images.cell) throw std::invalid_argument("hybrid stereo: the images were made for another cell");
  const gpu::HybridConstants grid = hybridGridConstants(c);
  requireSize(linearDepth, c, "linear depth");
  for (const vk::Image* image : {&images.leftMask, &images.rightMask}) requireSize(*image, c, "mask");
  for (const vk::Image* image : {&images.leftBins, &images.rightBins}) requireSize(*image, grid, "bins");
  const vk::ImageState previous = images.written ? kReadAnywhere : vk::kUndefined;
  for (const vk::Image* image : {&images.leftBins, &images.rightBins, &images.rowHistograms, &images.thresholds,
                                 &images.leftMask, &images.rightMask})
    vk::transition(cmd, *image, previous, vk::kComputeWrite);
  if (c.cell > 1) vk::transition(cmd, images.gridDepth, previous, vk::kComputeWrite);
  const vk::Image* classifiedDepth = &linearDepth;
  if (c.cell > 1) {  // the cells' nearest depths, classified as pixels; the pass zeroes the histogram too
    vk::transition(cmd, images.histogram, previous, vk::kComputeWrite);
    dispatch(*context_, cmd, gridDepth_.get(), gridDepthLayout_.layout,
             {&linearDepth, &images.gridDepth, &images.histogram}, c, groups(grid.width), groups(grid.height));
    vk::transition(cmd, images.gridDepth, vk::kComputeWrite, vk::kComputeRead);
    vk::transition(cmd, images.histogram, vk::kComputeWrite, kAtomics);
    classifiedDepth = &images.gridDepth;
  } else {
    vk::transition(cmd, images.histogram, previous, kCleared);
    const VkClearColorValue zero{};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, images.histogram.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    vk::transition(cmd, images.histogram, kCleared, kAtomics);
  }
  dispatch(*context_, cmd, classify_.forTaps(grid.baseTapCount), classifyLayout_.layout,
           {classifiedDepth, &images.leftBins, &images.rightBins, &images.histogram, &images.rowHistograms}, grid,
           std::uint32_t(grid.height), 1);
  mark();
  vk::transition(cmd, images.histogram, kAtomics, vk::kComputeRead);
  for (const vk::Image* image : {&images.rowHistograms, &images.leftBins, &images.rightBins})
    vk::transition(cmd, *image, vk::kComputeWrite, vk::kComputeRead);
  dispatch(*context_, cmd, threshold_.get(), thresholdLayout_.layout,
           {&images.histogram, &images.rowHistograms, &images.thresholds, &images.leftBins, &images.rightBins}, grid, 2,
           1);
  mark();
  vk::transition(cmd, images.thresholds, vk::kComputeWrite, vk::kComputeRead);
  dispatch(*context_, cmd, mask_.get(), maskLayout_.layout,
           {&images.leftBins, &images.rightBins, &images.thresholds, &images.leftMask, &images.rightMask}, c,
           groups((grid.width + shape_.maskRun - 1) / shape_.maskRun), groups(grid.height));
  mark();
  // Everything ends in one state, so the next frame (and the read-backs) start from one.
  for (const vk::Image* image : {&images.leftBins, &images.rightBins, &images.histogram, &images.rowHistograms,
                                 &images.thresholds})
    vk::transition(cmd, *image, vk::kComputeRead, vk::kComputeWrite);
  if (c.cell > 1) vk::transition(cmd, images.gridDepth, vk::kComputeRead, vk::kComputeWrite);
  images.written = true;
}

void HybridPass::recordComposite(VkCommandBuffer cmd, const vk::Image& eye, const vk::Image& renderedEye,
                                 const vk::Image& mask, const gpu::HybridConstants& c) const {
  requireSize(eye, c, "eye");
  requireSize(renderedEye, c, "rendered eye");
  requireSize(mask, c, "mask");
  dispatch(*context_, cmd, composite_.get(), compositeLayout_.layout, {&eye, &renderedEye, &mask}, c, groups(c.width),
           groups(c.height));
}

void HybridPass::recordCropEdges(VkCommandBuffer cmd, const vk::Image& eye, const gpu::HybridConstants& c) const {
  requireSize(eye, c, "eye");
  const int croppedColumns = c.cropBegin + (c.width - c.cropEnd);
  if (croppedColumns <= 0) return;
  dispatch(*context_, cmd, cropEdges_.get(), cropEdgesLayout_.layout, {&eye}, c, groups(croppedColumns),
           groups(c.height));
}

HybridHistogram HybridPass::readHistogram(vk::Context& context, const vk::Image& histogram, int row) {
  const std::vector<std::uint32_t> counts = readUints(context, histogram);
  HybridHistogram result{};
  for (std::size_t i = 0; i < result.size(); ++i) result[i] = counts[std::size_t(row) * S3D_HYBRID_BINS + i];
  return result;
}

HybridThreshold HybridPass::readThreshold(vk::Context& context, const vk::Image& thresholds, int row) {
  const std::vector<std::uint32_t> values = readUints(context, thresholds);
  const std::uint32_t* eye = values.data() + std::size_t(row) * S3D_HYBRID_THRESHOLD_FIELDS;
  return {int(eye[0]), eye[1], int(eye[2]), eye[3]};
}

std::vector<std::uint32_t> HybridPass::readBins(vk::Context& context, const vk::Image& bins) {
  return readUints(context, bins);
}

std::vector<std::uint8_t> HybridPass::readMask(vk::Context& context, const vk::Image& mask) {
  const std::vector<std::uint32_t> values = readUints(context, mask);
  return std::vector<std::uint8_t>(values.begin(), values.end());
}

HybridGpuResult classifyHybridOnGpu(vk::Context& context, const DepthImage& linearDepth,
                                    const gpu::HybridConstants& constants, std::optional<HybridRowShape> shape) {
  const HybridPass pass(context, shape);
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  const vk::Image depth = vk::createImage(context, VK_FORMAT_R32_SFLOAT, linearDepth.width, linearDepth.height, usage);
  vk::uploadImage(context, depth, std::as_bytes(std::span(linearDepth.pixels)), vk::kComputeRead);
  HybridPass::Images images = pass.createImages(linearDepth.width, linearDepth.height, constants.cell);
  context.submitAndWait([&](VkCommandBuffer cmd) { pass.recordMasks(cmd, depth, images, constants); });
  HybridGpuResult result;
  result.classification = {HybridPass::readBins(context, images.leftBins), HybridPass::readBins(context, images.rightBins),
                           HybridPass::readHistogram(context, images.histogram, 0),
                           HybridPass::readHistogram(context, images.histogram, 1)};
  result.leftThreshold = HybridPass::readThreshold(context, images.thresholds, 0);
  result.rightThreshold = HybridPass::readThreshold(context, images.thresholds, 1);
  result.leftMask = HybridPass::readMask(context, images.leftMask);
  result.rightMask = HybridPass::readMask(context, images.rightMask);
  return result;
}

ImageRGBA8 compositeHybridOnGpu(vk::Context& context, const ImageRGBA8& eye, const ImageRGBA8& rendered,
                                const std::vector<std::uint8_t>& mask, const gpu::HybridConstants& constants) {
  requireSameSize(eye, rendered, "hybrid composite (eye vs rendered eye)");
  const HybridPass pass(context);
  const VkImageUsageFlags usage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  auto image = [&](VkFormat format) { return vk::createImage(context, format, eye.width, eye.height, usage); };
  const vk::Image eyeImage = image(VK_FORMAT_R8G8B8A8_UNORM), renderedImage = image(VK_FORMAT_R8G8B8A8_UNORM),
                  maskImage = image(kUintFormat);
  const std::vector<std::uint32_t> maskTexels(mask.begin(), mask.end());
  vk::uploadImage(context, eyeImage, std::as_bytes(std::span(eye.pixels)), vk::kComputeWrite);
  vk::uploadImage(context, renderedImage, std::as_bytes(std::span(rendered.pixels)), vk::kComputeRead);
  vk::uploadImage(context, maskImage, std::as_bytes(std::span(maskTexels)), vk::kComputeRead);
  context.submitAndWait([&](VkCommandBuffer cmd) { pass.recordComposite(cmd, eyeImage, renderedImage, maskImage, constants); });
  ImageRGBA8 result(eye.width, eye.height);
  const std::vector<std::byte> bytes = vk::readbackImage(context, eyeImage, vk::kComputeWrite);
  std::memcpy(result.pixels.data(), bytes.data(), bytes.size());
  return result;
}

}  // namespace s3d::stereo
