#pragma once
// Shader modules, push-descriptor layouts and pipelines.
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "s3d/vk/context.h"
#include "s3d/vk/unique.h"

namespace s3d::vk {

Unique<VkShaderModule> createShaderModule(const Context& context, std::span<const std::uint32_t> spirv);

// A descriptor-set layout for vkCmdPushDescriptorSetKHR plus the pipeline layout around it.
struct PipelineLayout {
  Unique<VkDescriptorSetLayout> setLayout;
  Unique<VkPipelineLayout> layout;
};
PipelineLayout createPushDescriptorLayout(const Context& context,
                                          std::span<const VkDescriptorSetLayoutBinding> bindings,
                                          std::uint32_t pushConstantBytes, VkShaderStageFlags pushConstantStages);

// `specialization`: values of the shader's specialization constants (null: their defaults). Prints the driver's
// statistics when the context captures them (pipeline_statistics.h).
Unique<VkPipeline> createComputePipeline(const Context& context, VkPipelineLayout layout,
                                         std::span<const std::uint32_t> spirv,
                                         const VkSpecializationInfo* specialization = nullptr);

// Specialization constants of one 32-bit word each (a VkBool32 is one word), ids 0, 1, 2, ... in order.
class SpecializationWords {
 public:
  explicit SpecializationWords(std::vector<std::uint32_t> words);
  SpecializationWords(const SpecializationWords&) = delete;  // info() points into this object
  SpecializationWords& operator=(const SpecializationWords&) = delete;
  const VkSpecializationInfo* info() const { return &info_; }

 private:
  std::vector<std::uint32_t> words_;
  std::vector<VkSpecializationMapEntry> entries_;
  VkSpecializationInfo info_{};
};
Unique<VkPipeline> createComputePipeline(const Context& context, VkPipelineLayout layout,
                                         std::span<const std::uint32_t> spirv, const SpecializationWords& constants);

// Graphics pipeline for dynamic rendering (no render pass objects).
struct GraphicsPipelineDesc {
  std::span<const std::uint32_t> vertexSpirv;
  std::span<const std::uint32_t> fragmentSpirv;
  std::vector<VkVertexInputBindingDescription> vertexBindings;
  std::vector<VkVertexInputAttributeDescription> vertexAttributes;
  std::vector<VkFormat> colorFormats;  // VK_FORMAT_UNDEFINED: a location the render pass binds no image to
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  bool depthTest = false;
  bool depthWrite = false;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
  enum class Blend { None, Additive, Alpha };
  Blend blend = Blend::None;  // Additive: one + one; Alpha: src alpha over (1 - src alpha)
  VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
  // Rasterizer depth bias (shadow maps): constant in the format's depth units plus slope * max depth slope.
  float depthBiasConstant = 0.0f;
  float depthBiasSlope = 0.0f;
  // Values of the fragment shader's specialization constants (null: their defaults).
  const VkSpecializationInfo* fragmentSpecialization = nullptr;
};
Unique<VkPipeline> createGraphicsPipeline(const Context& context, VkPipelineLayout layout,
                                          const GraphicsPipelineDesc& desc);

// Descriptor-write helpers for push descriptors.
VkWriteDescriptorSet storageImageWrite(std::uint32_t binding, const VkDescriptorImageInfo* info);
VkWriteDescriptorSet sampledImageWrite(std::uint32_t binding, const VkDescriptorImageInfo* info);
VkWriteDescriptorSet uniformBufferWrite(std::uint32_t binding, const VkDescriptorBufferInfo* info);

}  // namespace s3d::vk
