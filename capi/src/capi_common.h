#pragma once
// What every C API entry point shares: the per-thread last error, the exception-to-result guard and the
// conversions of the C structs several functions take.
#include <stdexcept>
#include <string>

#include "capi_checks.h"
#include "s3d/s3d.h"
#include "s3d/stereo/eye_views.h"
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/vk/check.h"
#include "s3d/vk/context.h"

struct s3d_context_t {
  s3d::vk::Context context;
  std::uint32_t maxImageDimension2D;  // of the physical device the context was created with
};

namespace s3d::capi {

inline std::string& lastError() {
  thread_local std::string message;
  return message;
}

// For the functions without a result code: whether `pointer` is there, noting why not for s3d_last_error.
inline bool present(const void* pointer, const char* name) {
  if (pointer) {
    lastError().clear();
    return true;
  }
  lastError() = std::string(name) + " is NULL";
  return false;
}

// The Vulkan function and its result, without the C++ expression of its arguments.
inline std::string vulkanMessage(const vk::VulkanError& error) {
  const std::string text = error.what();
  return text.substr(0, text.find('(')) + " failed: " + vk::resultName(error.result());
}

template <typename F>
s3d_result guarded(F&& body) {
  std::string& message = lastError();
  try {
    body();
    message.clear();
    return S3D_SUCCESS;
  } catch (const std::invalid_argument& error) {
    message = error.what();
    return S3D_ERROR_INVALID_ARGUMENT;
  } catch (const vk::VulkanError& error) {
    message = vulkanMessage(error);
    return S3D_ERROR_VULKAN;
  } catch (const std::runtime_error& error) {  // adoption and patch failures name the missing requirement
    message = error.what();
    return S3D_ERROR_DEVICE_UNSUPPORTED;
  } catch (const std::exception& error) {
    message = error.what();
    return S3D_ERROR_UNKNOWN;
  } catch (...) {
    message = "unknown error";
    return S3D_ERROR_UNKNOWN;
  }
}

inline stereo::HostImage toCpp(const s3d_host_image& i) {
  return {i.image, i.view, i.format, i.layout, i.stage, i.access, i.layer};
}

inline stereo::HostProjection toCpp(const s3d_projection& p) {
  return {p.near_plane, p.far_plane, p.reversed_z != 0, p.infinite_far_plane != 0, p.first_person_depth_range,
          p.first_person_near, p.first_person_far};
}

// Each eye the stereo frame's size.
inline stereo::ViewConfiguration toCpp(const s3d_eye_views& v, std::uint32_t width, std::uint32_t height) {
  auto eye = [&](const s3d_eye_view& e) {
    return stereo::EyeView{e.position_x, e.angle_left, e.angle_right, e.angle_up, e.angle_down, width, height};
  };
  return {{eye(v.left), eye(v.right)}, v.world_scale};
}

}  // namespace s3d::capi
