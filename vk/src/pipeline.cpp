#include "s3d/vk/pipeline.h"

#include <utility>

#include "s3d/vk/check.h"
#include "s3d/vk/pipeline_statistics.h"

namespace s3d::vk {

Unique<VkShaderModule> createShaderModule(const Context& context, std::span<const std::uint32_t> spirv) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size_bytes();
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateShaderModule(context.device(), &info, context.allocator(), &module));
  return {context.device(), module, vkDestroyShaderModule, context.allocator()};
}

PipelineLayout createPushDescriptorLayout(const Context& context,
                                          std::span<const VkDescriptorSetLayoutBinding> bindings,
                                          std::uint32_t pushConstantBytes, VkShaderStageFlags pushConstantStages) {
  VkDevice device = context.device();
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateDescriptorSetLayout(device, &setInfo, context.allocator(), &setLayout));
  PipelineLayout result;
  result.setLayout = Unique<VkDescriptorSetLayout>(device, setLayout, vkDestroyDescriptorSetLayout, context.allocator());

  VkPushConstantRange range{pushConstantStages, 0, pushConstantBytes};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  layoutInfo.pushConstantRangeCount = pushConstantBytes > 0 ? 1 : 0;
  layoutInfo.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreatePipelineLayout(device, &layoutInfo, context.allocator(), &layout));
  result.layout = Unique<VkPipelineLayout>(device, layout, vkDestroyPipelineLayout, context.allocator());
  return result;
}

Unique<VkPipeline> createComputePipeline(const Context& context, VkPipelineLayout layout,
                                         std::span<const std::uint32_t> spirv,
                                         const VkSpecializationInfo* specialization) {
  Unique<VkShaderModule> module = createShaderModule(context, spirv);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization;
  info.layout = layout;
  if (context.capturesPipelineStatistics()) info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  VkPipeline pipeline = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateComputePipelines(context.device(), context.pipelineCache(), 1, &info, context.allocator(), &pipeline));
  if (context.capturesPipelineStatistics()) printPipelineStatistics(context.device(), pipeline, spirv.size(), specialization);
  return {context.device(), pipeline, vkDestroyPipeline, context.allocator()};
}

SpecializationWords::SpecializationWords(std::vector<std::uint32_t> words) : words_(std::move(words)) {
  for (std::uint32_t id = 0; id < words_.size(); ++id)
    entries_.push_back({id, std::uint32_t(id * sizeof(std::uint32_t)), sizeof(std::uint32_t)});
  info_ = {std::uint32_t(entries_.size()), entries_.data(), words_.size() * sizeof(std::uint32_t), words_.data()};
}

Unique<VkPipeline> createComputePipeline(const Context& context, VkPipelineLayout layout,
                                         std::span<const std::uint32_t> spirv, const SpecializationWords& constants) {
  return createComputePipeline(context, layout, spirv, constants.info());
}

namespace {

// Every colour attachment's blend state: all channels written, blended as desc.blend says.
std::vector<VkPipelineColorBlendAttachmentState> colorBlendAttachments(const GraphicsPipelineDesc& desc) {
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
  for (VkPipelineColorBlendAttachmentState& blend : blends) {
    blend.colorWriteMask =
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    if (desc.blend == GraphicsPipelineDesc::Blend::Additive) {
      blend.blendEnable = VK_TRUE;
      blend.srcColorBlendFactor = blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
      blend.srcAlphaBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
    } else if (desc.blend == GraphicsPipelineDesc::Blend::Alpha) {
      blend.blendEnable = VK_TRUE;
      blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;  // keep the opaque pass's alpha
      blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
    }
  }
  return blends;
}

}  // namespace

Unique<VkPipeline> createGraphicsPipeline(const Context& context, VkPipelineLayout layout,
                                          const GraphicsPipelineDesc& desc) {
  Unique<VkShaderModule> vertex = createShaderModule(context, desc.vertexSpirv);
  Unique<VkShaderModule> fragment = createShaderModule(context, desc.fragmentSpirv);
  VkPipelineShaderStageCreateInfo stages[2]{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertex;
  stages[0].pName = "main";
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragment;
  stages[1].pSpecializationInfo = desc.fragmentSpecialization;
  stages[1].pName = "main";

  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = static_cast<std::uint32_t>(desc.vertexBindings.size());
  vertexInput.pVertexBindingDescriptions = desc.vertexBindings.data();
  vertexInput.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(desc.vertexAttributes.size());
  vertexInput.pVertexAttributeDescriptions = desc.vertexAttributes.data();
  VkPipelineInputAssemblyStateCreateInfo inputAssembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  inputAssembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cullMode;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  raster.depthBiasEnable = desc.depthBiasConstant != 0.0f || desc.depthBiasSlope != 0.0f;
  raster.depthBiasConstantFactor = desc.depthBiasConstant;
  raster.depthBiasSlopeFactor = desc.depthBiasSlope;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depthTest;
  depth.depthWriteEnable = desc.depthWrite;
  depth.depthCompareOp = desc.depthCompare;
  const std::vector<VkPipelineColorBlendAttachmentState> blends = colorBlendAttachments(desc);
  VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  colorBlend.attachmentCount = static_cast<std::uint32_t>(blends.size());
  colorBlend.pAttachments = blends.data();
  VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &inputAssembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &colorBlend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateGraphicsPipelines(context.device(), context.pipelineCache(), 1, &info, context.allocator(), &pipeline));
  return {context.device(), pipeline, vkDestroyPipeline, context.allocator()};
}

static VkWriteDescriptorSet imageWrite(std::uint32_t binding, VkDescriptorType type,
                                       const VkDescriptorImageInfo* info) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pImageInfo = info;
  return write;
}

VkWriteDescriptorSet storageImageWrite(std::uint32_t binding, const VkDescriptorImageInfo* info) {
  return imageWrite(binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, info);
}

VkWriteDescriptorSet sampledImageWrite(std::uint32_t binding, const VkDescriptorImageInfo* info) {
  return imageWrite(binding, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, info);
}

VkWriteDescriptorSet uniformBufferWrite(std::uint32_t binding, const VkDescriptorBufferInfo* info) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
  write.pBufferInfo = info;
  return write;
}

}  // namespace s3d::vk
