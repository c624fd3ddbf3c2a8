#include "capi_validate.h"

#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "capi_common.h"
#include "s3d/hud/hud_pass_shared.h"
#include "s3d/number_text.h"
#include "s3d/stereo/detail/host_barriers.h"
#include "s3d/stereo/host_pass_shared.h"
#include "s3d/stereo/stereo.h"

namespace s3d::capi {
namespace {

constexpr std::uint32_t kBuiltInHudElements = 3;  // health, ammo, crosshair

bool isColorFormat(VkFormat f) {
  return f == VK_FORMAT_R8G8B8A8_UNORM || f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_UNORM ||
         f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R16G16B16A16_SFLOAT || f == VK_FORMAT_B10G11R11_UFLOAT_PACK32;
}

void requireIn(float value, float low, float high, Name name, bool highOpen = false) {  // (low, high] or (low, high)
  if (!(value > low && (highOpen ? value < high : value <= high)))
    fail(name.text() + " " + numberText(value) + " is outside (" + numberText(low) + ", " + numberText(high) +
         (highOpen ? ")" : "]"));
}

}  // namespace

void validateDevicePatch(VkPhysicalDevice physicalDevice, const VkDeviceCreateInfo* info, const void* out) {
  requireHandle(physicalDevice, {"physical_device"});
  requireNotNull(info, {"info"});
  requireNotNull(out, {"out"});
  if (info->sType != VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO)
    fail("info->sType is not VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO");
  if (info->enabledExtensionCount > 0) requireNotNull(info->ppEnabledExtensionNames, {"info->ppEnabledExtensionNames"});
}

void validateHostDevice(const s3d_host_device& host) {
  requireHandle(host.instance, {"s3d_host_device", "instance"});
  requireHandle(host.physical_device, {"s3d_host_device", "physical_device"});
  requireHandle(host.device, {"s3d_host_device", "device"});
  requireHandle(host.queue, {"s3d_host_device", "queue"});
  if (host.create_info && host.create_info->sType != VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO)
    fail("s3d_host_device.create_info->sType is not VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO");
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(host.physical_device, &count, families.data());
  if (host.queue_family >= count)
    fail("s3d_host_device.queue_family " + std::to_string(host.queue_family) + " is not below the device's " +
         std::to_string(count) + " queue families");
  if (!(families[host.queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT))
    fail("s3d_host_device.queue_family " + std::to_string(host.queue_family) + " has no compute (s3d records compute work)");
}

namespace {
// What the host pass and the stereo frame descriptions share: sizes for the output, the input formats.
void validateShape(const Name& name, std::uint32_t width, std::uint32_t height, std::int64_t output, VkFormat colorFormat,
                   VkFormat depthFormat, std::uint32_t maxImageDimension2D) {
  requireEnum(output, S3D_OUTPUT_TWO_EYES, S3D_OUTPUT_ANAGLYPH, name / "output");
  const bool sideBySide = output == S3D_OUTPUT_SIDE_BY_SIDE_FULL, topBottom = output == S3D_OUTPUT_TOP_BOTTOM_FULL;
  requireImageSize(width, maxImageDimension2D, name / "width", sideBySide ? 2 : 1, "S3D_OUTPUT_SIDE_BY_SIDE_FULL");
  requireImageSize(height, maxImageDimension2D, name / "height", topBottom ? 2 : 1, "S3D_OUTPUT_TOP_BOTTOM_FULL");
  if (output == S3D_OUTPUT_SIDE_BY_SIDE_HALF && width < 2)
    fail((name / "width").text() + " must be at least 2 for S3D_OUTPUT_SIDE_BY_SIDE_HALF");
  if (output == S3D_OUTPUT_TOP_BOTTOM_HALF && height < 2)
    fail((name / "height").text() + " must be at least 2 for S3D_OUTPUT_TOP_BOTTOM_HALF");
  if (!isColorFormat(colorFormat))
    fail((name / "color_format").text() + " " + std::to_string(int(colorFormat)) +
         " is not one of R8G8B8A8/B8G8R8A8 UNORM or SRGB, R16G16B16A16_SFLOAT, B10G11R11_UFLOAT_PACK32");
  if (!stereo::detail::isHostDepthFormat(depthFormat) && depthFormat != VK_FORMAT_R32_SFLOAT)
    fail((name / "depth_format").text() + " " + std::to_string(int(depthFormat)) +
         " is not one of D32_SFLOAT, D24_UNORM_S8_UINT, D16_UNORM or R32_SFLOAT linear depth");
}

bool isHdr(VkFormat f) { return f == VK_FORMAT_R16G16B16A16_SFLOAT || f == VK_FORMAT_B10G11R11_UFLOAT_PACK32; }

void requireFiniteMatrix(const float (&m)[16], Name name) {
  for (int i = 0; i < 16; ++i) requireFinite(m[i], {name.base, nullptr, i});
}
}  // namespace

void validate(const s3d_host_pass_desc& desc, std::uint32_t maxImageDimension2D) {
  validateShape({"s3d_host_pass_desc"}, desc.width, desc.height, rawEnum(desc.output), desc.color_format, desc.depth_format,
                maxImageDimension2D);
  if (desc.inputs_are_storage &&
      (desc.color_format != VK_FORMAT_R8G8B8A8_UNORM || desc.depth_format != VK_FORMAT_R32_SFLOAT))
    fail("s3d_host_pass_desc.inputs_are_storage needs color_format R8G8B8A8_UNORM and depth_format R32_SFLOAT");
}

void validate(const s3d_stereo_frame_desc& desc, std::uint32_t maxImageDimension2D) {
  const Name name{"s3d_stereo_frame_desc"};
  validateShape(name, desc.width, desc.height, rawEnum(desc.output), desc.color_format, desc.depth_format,
                maxImageDimension2D);
  const std::int64_t method = rawEnum(desc.method);
  requireEnum(method, S3D_METHOD_SEED, S3D_METHOD_HYBRID, name / "method");
  if (isHdr(desc.color_format) && method != S3D_METHOD_SEED && method != S3D_METHOD_SEARCH)
    fail("s3d_stereo_frame_desc.method S3D_METHOD_ITERATIVE, S3D_METHOD_FORWARD and S3D_METHOD_HYBRID displace 8-bit "
         "colour: with an HDR color_format use S3D_METHOD_SEED or S3D_METHOD_SEARCH");
  if (method == S3D_METHOD_HYBRID) {
    requireRange(desc.hybrid_budget, 0.0f, 1.0f, name / "hybrid_budget");
    if (desc.hybrid_cell < 0 || desc.hybrid_cell > stereo::kHybridCellLimit)
      fail("s3d_stereo_frame_desc.hybrid_cell " + std::to_string(desc.hybrid_cell) +
           " is not 0 (by the width), 1 or 2 pixels per side");
    requireRange(desc.hybrid_score_floor, 0.0f, stereo::kHybridScoreFloorLimit, name / "hybrid_score_floor");
    if (rawEnum(desc.output) != S3D_OUTPUT_TWO_EYES)
      fail("s3d_stereo_frame_desc.output must be S3D_OUTPUT_TWO_EYES for S3D_METHOD_HYBRID: the host draws into the "
           "eye images");
  }
  if ((method == S3D_METHOD_SEARCH || method == S3D_METHOD_HYBRID) && (desc.search_taps < 1 || desc.search_taps > S3D_STEREO_MAX_TAPS))
    fail("s3d_stereo_frame_desc.search_taps " + std::to_string(desc.search_taps) + " is outside [1, " +
         std::to_string(S3D_STEREO_MAX_TAPS) + "] for S3D_METHOD_SEARCH");
  if (method == S3D_METHOD_ITERATIVE && (desc.iterations < 1 || desc.iterations > 16))
    fail("s3d_stereo_frame_desc.iterations " + std::to_string(desc.iterations) + " is outside [1, 16] for "
         "S3D_METHOD_ITERATIVE");
  if (desc.previous_frame_fill && method != S3D_METHOD_FORWARD)
    fail("s3d_stereo_frame_desc.previous_frame_fill needs S3D_METHOD_FORWARD");
}

void validate(const s3d_eye_views& views, std::uint32_t width, std::uint32_t height, const char* name) {
  static constexpr const char* kFields[] = {"position_x", "angle_left", "angle_right", "angle_up",
                                            "angle_down", "width",      "height",      "world_scale"};
  const std::optional<stereo::EyeViewsProblem> found = stereo::eyeViewsProblem(toCpp(views, width, height), width, height);
  if (!found) return;
  const char* eye = found->eye == 0 ? "left." : found->eye == 1 ? "right." : "";
  fail(std::string(name) + eye + kFields[int(found->field)] + " " + found->problem);
}

void validate(const s3d_stereo_frame_dispatch& d, VkFormat colorFormat, VkFormat depthFormat, VkFormat eyeFormat,
              bool twoEyes, const char* centerCameraFor, std::uint32_t width, std::uint32_t height) {
  validateImage(&d.color, {"dispatch.color"}, ImageUse::Sampled);
  requireFormat(d.color, {"dispatch.color"}, colorFormat);
  validateImage(&d.depth, {"dispatch.depth"}, ImageUse::Sampled);
  requireFormat(d.depth, {"dispatch.depth"}, depthFormat);
  const std::pair<const s3d_host_image*, const char*> eyes[] = {{&d.left, "dispatch.left"}, {&d.right, "dispatch.right"}};
  const std::pair<const s3d_host_image*, const char*> packed[] = {{&d.target, "dispatch.target"}};
  using Outputs = std::span<const std::pair<const s3d_host_image*, const char*>>;
  for (const auto& [image, field] : twoEyes ? Outputs(eyes) : Outputs(packed)) {
    validateImage(image, {field}, ImageUse::StorageWrite);
    requireFormat(*image, {field}, eyeFormat);
  }
  if (twoEyes && d.left.image == d.right.image && d.left.layer == d.right.layer)
    fail("dispatch.right names the same image and layer as dispatch.left (one array image: layer 0 and layer 1)");
  if (depthFormat != VK_FORMAT_R32_SFLOAT) validate(d.projection, {"dispatch.projection"});
  if (d.eye_views) validate(*d.eye_views, width, height, "dispatch.eye_views->");
  // With eye views the separation and plane are derived: the defaults stand in for the ignored fields.
  const s3d_stereo_parameters parameters{d.eye_views ? 0.0f : d.max_separation,
                                         d.eye_views ? 1.0f : d.zero_parallax_distance,
                                         d.edge_crop,
                                         S3D_METHOD_SEED,
                                         1,
                                         d.weapon_depth_offset,
                                         d.weapon_depth_scale};
  validate(parameters, {"dispatch"});
  if (!centerCameraFor) return;
  requireFiniteMatrix(d.center_view, {"dispatch.center_view"});
  requireFiniteMatrix(d.center_projection, {"dispatch.center_projection"});
  if (!(d.center_projection[0] > 0.0f) || d.center_projection[11] == 0.0f)
    fail(std::string("dispatch.center_projection must be a perspective projection (element [0][0] > 0, [2][3] != 0) "
                     "for ") + centerCameraFor);
}

void validateHybridMasks(const s3d_stereo_frame_dispatch& d) {
  for (const auto& [mask, field] : {std::pair{&d.left_mask, "dispatch.left_mask"}, std::pair{&d.right_mask, "dispatch.right_mask"}}) {
    if (!mask->image)
      fail(std::string(field) + ".image is VK_NULL_HANDLE: S3D_METHOD_HYBRID writes each eye's mask into a "
                                "D32_SFLOAT depth image");
    requireFormat(*mask, {field}, VK_FORMAT_D32_SFLOAT);
    if (mask->layout == VK_IMAGE_LAYOUT_UNDEFINED || mask->layout == VK_IMAGE_LAYOUT_PREINITIALIZED)
      fail(std::string(field) + ".layout must be the layout the image is in, which it is left in (not UNDEFINED)");
    if (mask->stage == 0 && mask->layout != VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL && mask->layout != VK_IMAGE_LAYOUT_GENERAL)
      fail(std::string(field) + ".layout must be TRANSFER_DST_OPTIMAL or GENERAL when the host synchronizes it (stage 0)");
  }
  if (d.left_mask.image == d.right_mask.image && d.left_mask.layer == d.right_mask.layer)
    fail("dispatch.right_mask names the same image and layer as dispatch.left_mask");
}

void validate(const s3d_hud_pass_desc& desc, std::uint32_t maxImageDimension2D) {
  requireImageSize(desc.width, maxImageDimension2D, {"s3d_hud_pass_desc", "width"});
  requireImageSize(desc.height, maxImageDimension2D, {"s3d_hud_pass_desc", "height"});
  const std::uint32_t room = S3D_HUD_MAX_ELEMENTS - (desc.built_in ? kBuiltInHudElements : 0);
  if (desc.element_count > room)
    fail("s3d_hud_pass_desc.element_count " + std::to_string(desc.element_count) + " is above " +
         std::to_string(room) + " (a HUD pass has " + std::to_string(S3D_HUD_MAX_ELEMENTS) +
         " elements at most, the built-in ones included)");
  if (desc.element_count > 0) requireNotNull(desc.elements, {"s3d_hud_pass_desc", "elements"});
  for (std::uint32_t i = 0; i < desc.element_count; ++i) {
    const s3d_hud_element_desc& e = desc.elements[i];
    const Name element{"s3d_hud_pass_desc.elements", nullptr, i};
    requireFinite(e.placement.anchor_x, element / "placement.anchor_x");
    requireFinite(e.placement.anchor_y, element / "placement.anchor_y");
    requireImageSize(e.width, maxImageDimension2D, element / "width");
    requireImageSize(e.height, maxImageDimension2D, element / "height");
  }
}

void validate(const s3d_stereo_parameters& p, Name name) {
  requireRange(p.max_separation, 0.0f, stereo::kMaxSeparationLimit, name / "max_separation");
  requirePositive(p.zero_parallax_distance, name / "zero_parallax_distance");
  requireFinite(p.edge_crop, name / "edge_crop");
  if (p.edge_crop > stereo::kMaxSeparationLimit)
    fail((name / "edge_crop").text() + " " + numberText(p.edge_crop) + " is above " +
         numberText(stereo::kMaxSeparationLimit));
  const std::int64_t method = rawEnum(p.method);
  if (method == S3D_METHOD_ITERATIVE || method == S3D_METHOD_FORWARD)
    fail((name / "method").text() + " " + std::to_string(method) + " is for s3d_stereo_frame_record: "
         "s3d_stereo_parameters take S3D_METHOD_SEED or S3D_METHOD_SEARCH");
  requireEnum(method, S3D_METHOD_SEED, S3D_METHOD_SEARCH, name / "method");
  if (method == S3D_METHOD_SEARCH && (p.search_taps < 1 || p.search_taps > S3D_STEREO_MAX_TAPS))
    fail((name / "search_taps").text() + " " + std::to_string(p.search_taps) + " is outside [1, " +
         std::to_string(S3D_STEREO_MAX_TAPS) + "] for S3D_METHOD_SEARCH");
  requireNonNegative(p.weapon_depth_offset, name / "weapon_depth_offset");
  requirePositive(p.weapon_depth_scale, name / "weapon_depth_scale");
}

void validate(const s3d_projection& p, Name name) {
  requirePositive(p.near_plane, name / "near_plane");
  if (!p.infinite_far_plane && !(p.far_plane > p.near_plane && std::isfinite(p.far_plane)))
    fail((name / "far_plane").text() + " " + numberText(p.far_plane) + " must be finite and above near_plane " +
         numberText(p.near_plane) + " (or set infinite_far_plane)");
  requireRange(p.first_person_depth_range, 0.0f, 1.0f, name / "first_person_depth_range");
  if (p.first_person_depth_range == 1.0f) fail((name / "first_person_depth_range").text() + " must be below 1");
  if (p.first_person_depth_range == 0.0f) return;
  requirePositive(p.first_person_near, name / "first_person_near");
  if (!(p.first_person_far > p.first_person_near && std::isfinite(p.first_person_far)))
    fail((name / "first_person_far").text() + " " + numberText(p.first_person_far) +
         " must be finite and above first_person_near " + numberText(p.first_person_near));
}

void validateImage(const s3d_host_image* image, Name name, ImageUse use) {
  requireNotNull(image, name);
  requireHandle(image->image, name / "image");
  requireHandle(image->view, name / "view");
  if (image->stage != VK_PIPELINE_STAGE_2_NONE) return;  // s3d adds the barriers from any layout
  const bool usable = use == ImageUse::Sampled ? stereo::detail::sampledReadable(image->layout)
                                               : image->layout == VK_IMAGE_LAYOUT_GENERAL;
  if (!usable)
    fail((name / "layout").text() + " " + std::to_string(int(image->layout)) + " must be " +
         (use == ImageUse::Sampled ? "GENERAL or a read-only layout" : "VK_IMAGE_LAYOUT_GENERAL") +
         " when its stage is 0 (the host synchronizes it itself)");
}

void requireFormat(const s3d_host_image& image, Name name, VkFormat format, VkFormat alternative) {
  if (image.format == format || (alternative != VK_FORMAT_UNDEFINED && image.format == alternative)) return;
  fail((name / "format").text() + " " + std::to_string(int(image.format)) + " must be " + std::to_string(int(format)) +
       (alternative != VK_FORMAT_UNDEFINED ? " or " + std::to_string(int(alternative)) : std::string()));
}

void validate(const s3d_hud_element_frame* frames, std::uint32_t frameCount, std::uint32_t elementCount) {
  if (frameCount != elementCount)
    fail("frame_count " + std::to_string(frameCount) + " differs from the HUD pass's " + std::to_string(elementCount) +
         " elements (one s3d_hud_element_frame each)");
  if (frameCount > 0) requireNotNull(frames, {"frames"});
  for (std::uint32_t i = 0; i < frameCount; ++i) requireFinite(frames[i].parallax_px, {"frames", "parallax_px", i});
}

void validate(const s3d_frame_comfort_input& input) {
  const Name name{"s3d_frame_comfort_input"};
  for (int i = 0; i < 3; ++i) {
    requireFinite(input.camera_position[i], {"s3d_frame_comfort_input.camera_position", nullptr, i});
    requireFinite(input.camera_aim[i], {"s3d_frame_comfort_input.camera_aim", nullptr, i});
  }
  const float aimLength = std::hypot(input.camera_aim[0], input.camera_aim[1], input.camera_aim[2]);
  if (!(std::abs(aimLength - 1.0f) <= 1e-3f))
    fail("s3d_frame_comfort_input.camera_aim must be a unit vector (its length is " + numberText(aimLength) + ")");
  requirePositive(input.camera_near, name / "camera_near");
  validate(input.parameters, {"s3d_frame_comfort_input.parameters"});
  if (input.width == 0) fail("s3d_frame_comfort_input.width is 0");
  requirePositive(input.crosshair_distance, name / "crosshair_distance");
  requireNonNegative(input.crosshair_margin, name / "crosshair_margin");
  if (input.weapon_pixels > 0) {
    requirePositive(input.weapon_nearest_depth, name / "weapon_nearest_depth");
    requirePositive(input.weapon_farthest_depth, name / "weapon_farthest_depth");
    if (input.weapon_farthest_depth < input.weapon_nearest_depth)
      fail("s3d_frame_comfort_input.weapon_farthest_depth is below weapon_nearest_depth");
  }
  if (input.has_nearest_world_depth) requirePositive(input.nearest_world_depth, name / "nearest_world_depth");
  if (input.hud_count > 0) requireNotNull(input.hud_depths, name / "hud_depths");
  for (std::uint32_t i = 0; i < input.hud_count; ++i)
    requirePositive(input.hud_depths[i], {"s3d_frame_comfort_input.hud_depths", nullptr, i});
}

void validate(const s3d_frame_budget& budget, bool inputAllowsNegativeParallax, bool controllerAllowsNegativeParallax) {
  const Name name{"s3d_frame_budget"};
  if (inputAllowsNegativeParallax != controllerAllowsNegativeParallax)
    fail("s3d_frame_budget.controller was created with allow_negative_parallax " +
         std::to_string(int(controllerAllowsNegativeParallax)) + ", s3d_frame_comfort_input.allow_negative_parallax is " +
         std::to_string(int(inputAllowsNegativeParallax)));
  const s3d_depth_range& depth = budget.depth;
  if (std::isnan(depth.nearest) || std::isnan(depth.farthest))
    fail("s3d_frame_budget.depth.nearest and .farthest must not be NaN");
  if (depth.nearest <= depth.farthest) {  // a range with finite pixels
    requirePositive(depth.nearest, name / "depth.nearest");
    requirePositive(depth.farthest, name / "depth.farthest");
  }
  if (depth.histogram_bins > 0) requireNotNull(depth.histogram, name / "depth.histogram");
  requirePositive(budget.frame_seconds, name / "frame_seconds");
  if (budget.has_anticipated_nearest) requirePositive(budget.anticipated_nearest, name / "anticipated_nearest");
}

void validate(const s3d_display& display) {
  const Name name{"s3d_display"};
  requireIn(display.viewing_distance_meters, 0.0f, 100.0f, name / "viewing_distance_meters");
  requireRange(display.interocular_meters, 0.04f, 0.08f, name / "interocular_meters");
  if (display.field_of_view_degrees == 0.0f) {
    requireIn(display.screen_width_meters, 0.0f, 100.0f, name / "screen_width_meters");
    return;
  }
  requireIn(display.field_of_view_degrees, 0.0f, 170.0f, name / "field_of_view_degrees", true);
  // A head-mounted display's virtual screen spans the field of view at the focal distance.
  const double width = 2.0 * display.viewing_distance_meters * std::tan(display.field_of_view_degrees * 3.14159265358979 / 360.0);
  if (width > 100.0)
    fail("s3d_display.viewing_distance_meters and field_of_view_degrees make a virtual screen " + numberText(width) +
         " m wide, above 100 m");
}

}  // namespace s3d::capi
