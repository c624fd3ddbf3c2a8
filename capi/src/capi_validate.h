#pragma once
// The C API's structs checked field by field before any C++ type sees them (capi_checks.h's wording).
#include <cstdint>

#include "capi_checks.h"
#include "s3d/s3d.h"

namespace s3d::capi {

void validateDevicePatch(VkPhysicalDevice physicalDevice, const VkDeviceCreateInfo* info, const void* out);
void validateHostDevice(const s3d_host_device& host);

void validate(const s3d_host_pass_desc& desc, std::uint32_t maxImageDimension2D);
void validate(const s3d_hud_pass_desc& desc, std::uint32_t maxImageDimension2D);
void validate(const s3d_stereo_parameters& parameters, Name name);
void validate(const s3d_projection& projection, Name name = {"projection"});
void validate(const s3d_stereo_frame_desc& desc, std::uint32_t maxImageDimension2D);
// The views for width x height eyes, as the stereo frame takes them; `name` is how the caller reaches them
// ("views->", "dispatch.eye_views->").
void validate(const s3d_eye_views& views, std::uint32_t width, std::uint32_t height, const char* name);
// The images against the frame's formats and output, the parameters (or eye views), and the center camera when
// `centerCameraFor` names what needs it (the fill, the hybrid's eye cameras; null: nothing).
void validate(const s3d_stereo_frame_dispatch& dispatch, VkFormat colorFormat, VkFormat depthFormat, VkFormat eyeFormat,
              bool twoEyes, const char* centerCameraFor, std::uint32_t width, std::uint32_t height);
// The hybrid's mask images: present, D32_SFLOAT, a layout s3d can copy into, one per eye.
void validateHybridMasks(const s3d_stereo_frame_dispatch& dispatch);

// A host image s3d reads (sampled, or storage when `storage`) or writes (storage): handles, format and, when the
// host synchronizes it itself (stage 0), a layout s3d can use as it is.
enum class ImageUse { Sampled, StorageRead, StorageWrite };
void validateImage(const s3d_host_image* image, Name name, ImageUse use);
void requireFormat(const s3d_host_image& image, Name name, VkFormat format, VkFormat alternative = VK_FORMAT_UNDEFINED);

void validate(const s3d_hud_element_frame* frames, std::uint32_t frameCount, std::uint32_t elementCount);
void validate(const s3d_frame_comfort_input& input);
void validate(const s3d_frame_budget& budget, bool inputAllowsNegativeParallax, bool controllerAllowsNegativeParallax);
void validate(const s3d_display& display);

}  // namespace s3d::capi
