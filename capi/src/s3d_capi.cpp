// The C API over the C++ library: every entry point catches, stores the message per thread and returns a code.
#include "s3d/s3d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "capi_comfort.h"
#include "capi_common.h"
#include "capi_validate.h"
#include "s3d/comfort/frame_comfort_state.h"
#include "s3d/number_text.h"
#include "s3d/hud/hud_pass.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/vk/check.h"
#include "s3d/vk/context.h"

struct s3d_host_pass_t {
  s3d::stereo::HostStereoPass pass;
};
struct s3d_hud_pass_t {
  s3d::hud::HudPass pass;
};
struct s3d_budget_controller_t {
  s3d::comfort::DisparityBudgetController controller;
};
struct s3d_device_patch_t {
  std::unique_ptr<s3d::vk::DeviceRequirementsPatch> patch;
};

namespace {

using s3d::capi::guarded;
using s3d::capi::ImageUse;
using s3d::capi::lastError;
using s3d::capi::Name;
using s3d::capi::present;
using s3d::capi::requireNotNull;
using s3d::capi::toC;
using s3d::capi::toCpp;

// One frame's HUD in C++ types, held on the stack: record() allocates nothing per frame.
struct HudFrameStorage {
  std::array<s3d::hud::HudElementFrame, S3D_HUD_MAX_ELEMENTS> frames{};
  std::array<s3d::stereo::HostImage, S3D_HUD_MAX_ELEMENTS> hostLayers{};
  std::span<const s3d::hud::HudElementFrame> frameSpan;
  std::span<const s3d::stereo::HostImage> hostLayerSpan;

  HudFrameStorage(const s3d::hud::HudPass& pass, const s3d_hud_element_frame* frames_, uint32_t frameCount,
                  const s3d_host_image* hostLayers_, uint32_t hostLayerCount) {
    s3d::capi::validate(frames_, frameCount, uint32_t(pass.desc().elements.size()));
    if (hostLayerCount != pass.hostLayerCount())
      s3d::capi::fail("host_layer_count " + std::to_string(hostLayerCount) + " differs from the HUD pass's " +
                      std::to_string(pass.hostLayerCount()) + " host layers (elements made without pixels)");
    if (hostLayerCount > 0) requireNotNull(hostLayers_, {"host_layers"});
    for (uint32_t i = 0; i < hostLayerCount; ++i) {
      const Name name{"host_layers", nullptr, i};
      s3d::capi::validateImage(&hostLayers_[i], name, ImageUse::Sampled);
      s3d::capi::requireFormat(hostLayers_[i], name, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM);
      hostLayers[i] = toCpp(hostLayers_[i]);
    }
    for (uint32_t i = 0; i < frameCount; ++i)
      frames[i] = {frames_[i].parallax_px, frames_[i].fades_behind_weapon != 0, frames_[i].hidden != 0};
    frameSpan = std::span(frames).first(frameCount);
    hostLayerSpan = std::span(hostLayers).first(hostLayerCount);
  }
};

void validateOutput(const s3d_host_image* image, const char* name, VkFormat eyeFormat) {
  s3d::capi::validateImage(image, {name}, ImageUse::StorageWrite);
  s3d::capi::requireFormat(*image, {name}, eyeFormat);
}

// The images record() reads and writes, checked against what the pass was made for.
void validateImages(const s3d::stereo::HostStereoPass& pass, const s3d_host_image* color, const s3d_host_image* depth,
                    const s3d_host_image* left, const s3d_host_image* right, const s3d_host_image* target) {
  const s3d::stereo::HostStereoPassDesc& desc = pass.desc();
  const ImageUse input = desc.inputsAreStorage ? ImageUse::StorageRead : ImageUse::Sampled;
  s3d::capi::validateImage(color, {"color"}, input);
  s3d::capi::requireFormat(*color, {"color"}, desc.colorFormat);
  s3d::capi::validateImage(depth, {"depth"}, input);
  s3d::capi::requireFormat(*depth, {"depth"}, desc.depthFormat);
  if (desc.output == s3d::stereo::HostOutput::TwoEyes) {
    validateOutput(left, "left", pass.eyeFormat());
    validateOutput(right, "right", pass.eyeFormat());
    if (target) s3d::capi::fail("target must be NULL for S3D_OUTPUT_TWO_EYES (left and right get the eyes)");
  } else {
    validateOutput(target, "target", pass.eyeFormat());
    if (left || right) s3d::capi::fail("left and right must be NULL for packed outputs (target gets the eyes)");
  }
}

void recordHostPass(s3d_host_pass pass, VkCommandBuffer cmd, const s3d_host_image* color, const s3d_host_image* depth,
                    const s3d_stereo_parameters* parameters, const s3d_projection* projection,
                    const s3d_host_image* left, const s3d_host_image* right, const s3d_host_image* target,
                    const s3d::stereo::EyeOverlay* overlay) {
  requireNotNull(pass, {"pass"});
  s3d::capi::requireHandle(cmd, {"cmd"});
  requireNotNull(parameters, {"parameters"});
  s3d::capi::validate(*parameters, {"parameters"});
  const s3d::stereo::HostStereoPassDesc& desc = pass->pass.desc();
  if (projection)
    s3d::capi::validate(*projection);
  else if (desc.depthFormat != VK_FORMAT_R32_SFLOAT)
    s3d::capi::fail("projection is NULL: the pass's hardware depth_format needs the s3d_projection");
  validateImages(pass->pass, color, depth, left, right, target);
  const s3d::stereo::StereoParameters cpp = toCpp(*parameters);
  s3d::stereo::HostFrame frame;
  frame.stereo = s3d::stereo::makeStereoConstants(cpp, desc.width, desc.height);
  if (projection)
    frame.projection = toCpp(*projection);
  frame.weaponDepthOffset = cpp.weaponDepthOffset;
  frame.weaponDepthScale = cpp.weaponDepthScale;
  const s3d::stereo::HostImage leftImage = left ? toCpp(*left) : s3d::stereo::HostImage{};
  const s3d::stereo::HostImage rightImage = right ? toCpp(*right) : s3d::stereo::HostImage{};
  const s3d::stereo::HostImage targetImage = target ? toCpp(*target) : s3d::stereo::HostImage{};
  pass->pass.record(cmd, toCpp(*color), toCpp(*depth), frame, left ? &leftImage : nullptr,
                    right ? &rightImage : nullptr, target ? &targetImage : nullptr, overlay);
}

// The same wording as Context's own check, in the C API's terms: the host's device lacks a requirement.
void requireDeviceSupport(const s3d_host_device& host) {
  std::vector<std::string> missing = s3d::vk::missingDeviceSupport(host.physical_device);
  const bool supported = missing.empty();
  if (supported && host.create_info) missing = s3d::vk::missingEnabledRequirements(*host.create_info);
  if (missing.empty()) return;
  std::string names;
  for (const std::string& name : missing) names += (names.empty() ? "" : ", ") + name;
  throw std::runtime_error(supported ? "s3d_host_device.device was created without " + names +
                                           " (patch its VkDeviceCreateInfo with s3d_device_patch_apply)"
                                     : "s3d_host_device.physical_device does not support " + names);
}

const s3d::vk::DeviceRequirements& requirements() {
  static const s3d::vk::DeviceRequirements value = s3d::vk::deviceRequirements();
  return value;
}

}  // namespace

extern "C" {

const char* s3d_last_error(void) { return lastError().c_str(); }

uint32_t s3d_required_api_version(void) { return requirements().apiVersion; }
uint32_t s3d_required_extension_count(void) { return uint32_t(requirements().extensions.size()); }
const char* s3d_required_extension(uint32_t index) {
  const auto& names = requirements().extensions;
  return present(index < names.size() ? &names : nullptr, "index past s3d_required_extension_count(): the name")
             ? names[index].c_str()
             : nullptr;
}
uint32_t s3d_required_feature_count(void) { return uint32_t(requirements().features.size()); }
const char* s3d_required_feature(uint32_t index) {
  const auto& names = requirements().features;
  return present(index < names.size() ? &names : nullptr, "index past s3d_required_feature_count(): the name")
             ? names[index].c_str()
             : nullptr;
}

s3d_result s3d_device_patch_apply(VkPhysicalDevice physical_device, VkDeviceCreateInfo* info, s3d_device_patch* out) {
  return guarded([&] {
    s3d::capi::validateDevicePatch(physical_device, info, out);
    auto patch = std::make_unique<s3d_device_patch_t>();
    patch->patch = std::make_unique<s3d::vk::DeviceRequirementsPatch>(physical_device, *info);
    *out = patch.release();
  });
}
void s3d_device_patch_destroy(s3d_device_patch patch) { delete patch; }

s3d_result s3d_context_create(const s3d_host_device* host, s3d_context* out) {
  return guarded([&] {
    requireNotNull(host, {"host"});
    requireNotNull(out, {"out"});
    s3d::capi::validateHostDevice(*host);
    requireDeviceSupport(*host);
    s3d::vk::HostDevice device;
    device.instance = host->instance;
    device.physicalDevice = host->physical_device;
    device.device = host->device;
    device.queueFamily = host->queue_family;
    device.queue = host->queue;
    device.allocator = host->allocator;
    device.pipelineCache = host->pipeline_cache;
    device.createInfo = host->create_info;
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(host->physical_device, &properties);
    *out = new s3d_context_t{s3d::vk::Context(device), properties.limits.maxImageDimension2D};
  });
}
void s3d_context_destroy(s3d_context context) { delete context; }

void s3d_default_stereo_parameters(s3d_stereo_parameters* out) {
  if (present(out, "out")) *out = toC(s3d::stereo::StereoParameters{});
}

s3d_result s3d_host_pass_create(s3d_context context, const s3d_host_pass_desc* desc, s3d_host_pass* out) {
  return guarded([&] {
    requireNotNull(context, {"context"});
    requireNotNull(desc, {"desc"});
    requireNotNull(out, {"out"});
    s3d::capi::validate(*desc, context->maxImageDimension2D);
    const s3d::stereo::HostStereoPassDesc cpp{desc->width, desc->height, desc->color_format, desc->depth_format,
                                              s3d::stereo::HostOutput(desc->output), desc->inputs_are_storage != 0};
    *out = new s3d_host_pass_t{s3d::stereo::HostStereoPass(context->context, cpp)};
  });
}
void s3d_host_pass_destroy(s3d_host_pass pass) { delete pass; }
VkFormat s3d_host_pass_eye_format(s3d_host_pass pass) {
  return present(pass, "pass") ? pass->pass.eyeFormat() : VK_FORMAT_UNDEFINED;
}
void s3d_host_pass_packed_size(s3d_host_pass pass, uint32_t* width, uint32_t* height) {
  const bool valid = present(pass, "pass");
  if (width) *width = valid ? pass->pass.packedWidth() : 0;
  if (height) *height = valid ? pass->pass.packedHeight() : 0;
}

s3d_result s3d_host_pass_record(s3d_host_pass pass, VkCommandBuffer cmd, const s3d_host_image* color,
                                const s3d_host_image* depth, const s3d_stereo_parameters* parameters,
                                const s3d_projection* projection, const s3d_host_image* left,
                                const s3d_host_image* right, const s3d_host_image* target) {
  return guarded([&] { recordHostPass(pass, cmd, color, depth, parameters, projection, left, right, target, nullptr); });
}

s3d_result s3d_hud_pass_create(s3d_context context, const s3d_hud_pass_desc* desc, s3d_hud_pass* out) {
  return guarded([&] {
    requireNotNull(context, {"context"});
    requireNotNull(desc, {"desc"});
    requireNotNull(out, {"out"});
    s3d::capi::validate(*desc, context->maxImageDimension2D);
    s3d::hud::HudPassDesc cpp{desc->width, desc->height, {}};
    if (desc->built_in)
      for (const s3d::hud::HudLayer& layer : s3d::hud::builtInHudLayers(desc->width, desc->height))
        cpp.elements.push_back(s3d::hud::HudPassElement::uploaded(layer));
    for (uint32_t i = 0; i < desc->element_count; ++i) {
      const s3d_hud_element_desc& e = desc->elements[i];
      const std::string name = e.name ? e.name : "element " + std::to_string(i);
      const s3d::hud::HudPlacement placement{e.placement.anchor_x, e.placement.anchor_y, e.placement.pivot_x,
                                             e.placement.pivot_y};
      if (!e.pixels) {
        cpp.elements.push_back(s3d::hud::HudPassElement::hostLayer(name, e.width, e.height, placement));
        continue;
      }
      s3d::hud::HudLayer layer{name, s3d::ImageRGBA8(e.width, e.height), placement};
      std::copy_n(e.pixels, layer.pixels.pixels.size(), layer.pixels.pixels.data());
      cpp.elements.push_back(s3d::hud::HudPassElement::uploaded(layer));
    }
    *out = new s3d_hud_pass_t{s3d::hud::HudPass(context->context, cpp)};
  });
}
void s3d_hud_pass_destroy(s3d_hud_pass pass) { delete pass; }
uint32_t s3d_hud_pass_element_count(s3d_hud_pass pass) {
  return present(pass, "pass") ? uint32_t(pass->pass.desc().elements.size()) : 0;
}

s3d_result s3d_hud_pass_record(s3d_hud_pass pass, VkCommandBuffer cmd, const s3d_hud_element_frame* frames,
                               uint32_t frame_count, const s3d_host_image* host_layers, uint32_t host_layer_count,
                               const s3d_host_image* left, const s3d_host_image* right) {
  return guarded([&] {
    requireNotNull(pass, {"pass"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    const HudFrameStorage hud(pass->pass, frames, frame_count, host_layers, host_layer_count);
    validateOutput(left, "left", s3d::hud::HudPass::eyeFormat());
    validateOutput(right, "right", s3d::hud::HudPass::eyeFormat());
    pass->pass.record(cmd, hud.frameSpan, hud.hostLayerSpan, toCpp(*left), toCpp(*right));
  });
}

s3d_result s3d_host_pass_record_with_hud(s3d_host_pass pass, VkCommandBuffer cmd, const s3d_host_image* color,
                                         const s3d_host_image* depth, const s3d_stereo_parameters* parameters,
                                         const s3d_projection* projection, const s3d_host_image* left,
                                         const s3d_host_image* right, const s3d_host_image* target, s3d_hud_pass hud,
                                         const s3d_hud_element_frame* frames, uint32_t frame_count,
                                         const s3d_host_image* host_layers, uint32_t host_layer_count) {
  return guarded([&] {
    requireNotNull(pass, {"pass"});
    requireNotNull(hud, {"hud"});
    const s3d::stereo::HostStereoPassDesc& desc = pass->pass.desc();
    if (hud->pass.desc().width != desc.width || hud->pass.desc().height != desc.height)
      s3d::capi::fail("hud was made for " + std::to_string(hud->pass.desc().width) + "x" +
                      std::to_string(hud->pass.desc().height) + " eyes, pass for " + std::to_string(desc.width) + "x" +
                      std::to_string(desc.height));
    if (pass->pass.eyeFormat() != s3d::hud::HudPass::eyeFormat())
      s3d::capi::fail("hud needs 8-bit eyes: pass was made with an HDR s3d_host_pass_desc.color_format");
    const HudFrameStorage storage(hud->pass, frames, frame_count, host_layers, host_layer_count);
    const s3d::hud::HudOverlay overlay = hud->pass.overlay(storage.frameSpan, storage.hostLayerSpan);
    recordHostPass(pass, cmd, color, depth, parameters, projection, left, right, target, &overlay);
  });
}

s3d_result s3d_frame_comfort_state_compute(const s3d_frame_comfort_input* input, s3d_frame_comfort_state* out,
                                           s3d_hud_element_state* hud_states) {
  return s3d_frame_comfort_state_compute_budgeted(input, nullptr, out, hud_states, nullptr);
}

s3d_result s3d_budget_controller_create(const s3d_display* display, int32_t allow_negative_parallax,
                                        s3d_budget_controller* out) {
  return guarded([&] {
    requireNotNull(display, {"display"});
    requireNotNull(out, {"out"});
    s3d::capi::validate(*display);
    const s3d::comfort::DisplayProfile profile = s3d::capi::toCpp(*display);
    *out = new s3d_budget_controller_t{
        s3d::comfort::DisparityBudgetController(s3d::comfort::disparityBudget(profile), allow_negative_parallax != 0)};
  });
}
void s3d_budget_controller_destroy(s3d_budget_controller controller) { delete controller; }

s3d_result s3d_frame_comfort_state_compute_budgeted(const s3d_frame_comfort_input* input,
                                                    const s3d_frame_budget* budget, s3d_frame_comfort_state* out,
                                                    s3d_hud_element_state* hud_states, s3d_budget_choice* choice) {
  return guarded([&] {
    requireNotNull(input, {"input"});
    requireNotNull(out, {"out"});
    s3d::capi::validate(*input);
    if (input->hud_count > 0) requireNotNull(hud_states, {"hud_states"});
    if (budget) {
      requireNotNull(budget->controller, {"s3d_frame_budget", "controller"});
      s3d::capi::validate(*budget, input->allow_negative_parallax != 0,
                          budget->controller->controller.allowsNegativeParallax());
    }
    s3d::comfort::FrameComfortInput cpp = s3d::capi::toCpp(*input);
    s3d::stereo::DepthRange range;
    if (budget) {
      const s3d_depth_range& depth = budget->depth;
      const bool finite = depth.nearest <= depth.farthest;
      range.nearest = finite ? depth.nearest : std::numeric_limits<float>::infinity();
      range.farthest = finite ? depth.farthest : 0.0f;
      range.skyPixels = depth.sky_pixels;
      if (depth.histogram) range.bins.assign(depth.histogram, depth.histogram + depth.histogram_bins);
      s3d::comfort::FrameBudget frame{&budget->controller->controller, &range, budget->frame_seconds,
                                      budget->camera_cut != 0};
      if (budget->has_anticipated_nearest) frame.anticipatedNearest = budget->anticipated_nearest;
      frame.receding = budget->receding != 0;
      cpp.budget = frame;
    }
    const s3d::comfort::FrameComfortState state = s3d::comfort::frameComfortState(cpp);
    s3d::capi::toC(state, input->hud_count, out, hud_states);
    if (choice) *choice = budget ? s3d::capi::toC(state.budget, budget->controller->controller.budget()) : s3d_budget_choice{};
  });
}

}  // extern "C"
