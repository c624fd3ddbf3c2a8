#include "host_scene.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

// SPIR-V compiled from shaders/ by glslangValidator when this host is built (its CMakeLists.txt).
#include "scene_frag.h"
#include "scene_vert.h"

namespace host {
namespace {

struct Vertex {
  glm::vec3 position, normal;
};

struct DrawConstants {  // the shaders' push-constant block: 128 bytes, the minimum every device offers
  glm::mat4 clipFromObject;
  glm::vec4 worldFromObjectRows[3];
  glm::vec4 color;
};
static_assert(sizeof(DrawConstants) == 128);

// A cube from -1 to 1: 6 faces of 4 vertices with their normal, 2 triangles each.
void cube(std::vector<Vertex>& vertices, std::vector<std::uint16_t>& indices) {
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    const glm::vec3 u = glm::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 v = glm::cross(n, u);
    const auto base = std::uint16_t(vertices.size());
    for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      vertices.push_back({n + c.x * u + c.y * v, n});
    for (const int i : {0, 1, 2, 0, 2, 3}) indices.push_back(std::uint16_t(base + i));
  }
}

VkShaderModule shaderModule(VkDevice device, const std::uint32_t* code, std::size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = code;
  VkShaderModule module = VK_NULL_HANDLE;
  HOST_VK(vkCreateShaderModule(device, &info, nullptr, &module));
  return module;
}

glm::mat4 projection(float fovY, float aspect, float nearPlane, float farPlane) {
  glm::mat4 p = glm::perspectiveRH_ZO(fovY, aspect, nearPlane, farPlane);  // Vulkan's 0..1 depth
  p[1][1] = -p[1][1];                                                    // and its y down
  return p;
}

DrawConstants drawConstants(const glm::mat4& clipFromWorld, const Box& box, float mask) {
  const glm::mat4 worldFromObject = glm::scale(glm::translate(glm::mat4(1.0f), box.center), box.halfSize);
  DrawConstants c{};
  c.clipFromObject = clipFromWorld * worldFromObject;
  const glm::mat4 rows = glm::transpose(worldFromObject);
  for (int i = 0; i < 3; ++i) c.worldFromObjectRows[i] = rows[i];
  c.color = glm::vec4(box.color, mask);
  return c;
}

// The scene's pipeline (dynamic rendering): sRGB colour and D32 depth with depth test LESS, no culling.
VkPipeline createPipeline(VkDevice device, VkPipelineLayout layout) {
  const VkShaderModule vert = shaderModule(device, scene_vert, sizeof scene_vert);
  const VkShaderModule frag = shaderModule(device, scene_frag, sizeof scene_frag);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vert;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = frag;
  stages[1].pName = "main";
  const VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[2] = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)}};
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = 1;
  vertexInput.pVertexBindingDescriptions = &binding;
  vertexInput.vertexAttributeDescriptionCount = 2;
  vertexInput.pVertexAttributeDescriptions = attributes;
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                                   VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &blendAttachment;
  const VkDynamicState dynamicStates[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;
  const VkFormat colorFormat = VK_FORMAT_R8G8B8A8_SRGB;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &colorFormat;
  rendering.depthAttachmentFormat = VK_FORMAT_D32_SFLOAT;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  const VkResult created = vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
  vkDestroyShaderModule(device, vert, nullptr);
  vkDestroyShaderModule(device, frag, nullptr);
  HOST_VK(created);
  return pipeline;
}

}  // namespace

Scene::Scene(const Device& device, std::uint32_t width, std::uint32_t height)
    : device_(device), width_(width), height_(height) {
  world_ = {
      {{0.0f, -0.05f, -10.0f}, {8.0f, 0.05f, 12.0f}, {0.55f, 0.52f, 0.48f}},  // floor
      {{0.0f, 3.0f, -20.0f}, {8.0f, 3.0f, 0.1f}, {0.62f, 0.45f, 0.35f}},      // back wall
      {{-8.0f, 3.0f, -10.0f}, {0.1f, 3.0f, 12.0f}, {0.40f, 0.50f, 0.60f}},    // left wall
      {{8.0f, 3.0f, -10.0f}, {0.1f, 3.0f, 12.0f}, {0.45f, 0.58f, 0.40f}},     // right wall
      {{0.3f, 1.0f, -5.0f}, {0.6f, 1.0f, 0.6f}, {0.85f, 0.65f, 0.20f}},       // the box the crosshair rests on
      {{-2.2f, 0.6f, -3.5f}, {0.5f, 0.6f, 0.5f}, {0.75f, 0.25f, 0.25f}},
      {{2.6f, 1.5f, -9.0f}, {0.8f, 1.5f, 0.8f}, {0.30f, 0.55f, 0.80f}},
  };
  weapon_ = {{0.28f, -0.22f, -0.45f}, {0.05f, 0.04f, 0.2f}, {0.30f, 0.30f, 0.34f}};

  std::vector<Vertex> vertices;
  std::vector<std::uint16_t> indices;
  cube(vertices, indices);
  vertices_.emplace(device, vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  indices_.emplace(device, indices.size() * sizeof(std::uint16_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(vertices_->mapped, vertices.data(), vertices.size() * sizeof(Vertex));
  std::memcpy(indices_->mapped, indices.data(), indices.size() * sizeof(std::uint16_t));

  VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &push;
  HOST_VK(vkCreatePipelineLayout(device.device, &layoutInfo, nullptr, &layout_));

  pipeline_ = createPipeline(device.device, layout_);
}

Scene::~Scene() {
  vkDestroyPipeline(device_.device, pipeline_, nullptr);
  vkDestroyPipelineLayout(device_.device, layout_, nullptr);
}

void Scene::record(VkCommandBuffer cmd, const Image& color, const Image& depth) const {
  VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  colorAttachment.imageView = color.view;
  colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colorAttachment.clearValue.color = {{0.45f, 0.60f, 0.85f, 1.0f}};  // sky; alpha 1: not the weapon
  VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depthAttachment.imageView = depth.view;
  depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depthAttachment.clearValue.depthStencil = {1.0f, 0};  // the far plane: sky
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, {width_, height_}};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &colorAttachment;
  rendering.pDepthAttachment = &depthAttachment;
  vkCmdBeginRendering(cmd, &rendering);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  const VkDeviceSize offset = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertices_->buffer, &offset);
  vkCmdBindIndexBuffer(cmd, indices_->buffer, 0, VK_INDEX_TYPE_UINT16);
  const VkRect2D scissor{{0, 0}, {width_, height_}};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  const float aspect = float(width_) / float(height_);
  const float split = camera_.firstPersonDepthRange;
  auto draw = [&](const DrawConstants& constants) {
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof constants,
                       &constants);
    vkCmdDrawIndexed(cmd, 36, 1, 0, 0, 0);
  };

  // The world: its projection into device depth [split, 1].
  VkViewport viewport{0.0f, 0.0f, float(width_), float(height_), split, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  const glm::mat4 view = glm::lookAt(camera_.position, camera_.position + camera_.forward, glm::vec3(0, 1, 0));
  const glm::mat4 clipFromWorld = projection(camera_.verticalFov, aspect, camera_.nearPlane, camera_.farPlane) * view;
  for (const Box& box : world_) draw(drawConstants(clipFromWorld, box, 1.0f));

  // The first-person object: its own near/far into device depth [0, split], so it is never behind the world;
  // alpha 0 marks it (the weapon mask).
  viewport.minDepth = 0.0f;
  viewport.maxDepth = split;
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  draw(drawConstants(projection(camera_.verticalFov, aspect, camera_.weaponNear, camera_.weaponFar), weapon_, 0.0f));
  vkCmdEndRendering(cmd);
}

std::optional<float> Scene::rayCast(glm::vec3 origin, glm::vec3 direction, float maxDistance) const {
  std::optional<float> nearest;
  for (const Box& box : world_) {  // slab test
    float enter = 0.0f, leave = maxDistance;
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = box.center[axis] - box.halfSize[axis], hi = box.center[axis] + box.halfSize[axis];
      if (std::abs(direction[axis]) < 1e-12f) {
        if (origin[axis] < lo || origin[axis] > hi) enter = std::numeric_limits<float>::infinity();
        continue;
      }
      float t0 = (lo - origin[axis]) / direction[axis], t1 = (hi - origin[axis]) / direction[axis];
      if (t0 > t1) std::swap(t0, t1);
      enter = std::max(enter, t0);
      leave = std::min(leave, t1);
    }
    if (enter <= leave && (!nearest || enter < *nearest)) nearest = enter;
  }
  return nearest;
}

glm::vec2 Scene::weaponDepthRange() const {
  return {-(weapon_.center.z + weapon_.halfSize.z), -(weapon_.center.z - weapon_.halfSize.z)};
}

}  // namespace host
