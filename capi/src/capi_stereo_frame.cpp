// The C API's stereo frame over stereo::StereoFrame: the C structs checked field by field, then converted on the
// stack (recording allocates nothing).
#include "capi_stereo_frame.h"

#include <cmath>
#include <cstring>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "capi_common.h"
#include "capi_validate.h"

struct s3d_stereo_frame_t {
  s3d::stereo::StereoFrame frame;
};

namespace s3d::capi {
namespace {

stereo::StereoMethod toCpp(s3d_method method) {
  switch (method) {
    case S3D_METHOD_SEED: return s3d::stereo::StereoMethod::Seed;
    case S3D_METHOD_ITERATIVE: return s3d::stereo::StereoMethod::Iterative;
    case S3D_METHOD_FORWARD: return s3d::stereo::StereoMethod::Forward;
    case S3D_METHOD_HYBRID: return s3d::stereo::StereoMethod::Hybrid;
    default: return s3d::stereo::StereoMethod::Search;
  }
}

}  // namespace

stereo::StereoFrameDesc checkedDesc(const s3d_stereo_frame_desc& desc, std::uint32_t maxImageDimension2D) {
  validate(desc, maxImageDimension2D);
  stereo::StereoFrameDesc cpp;
  cpp.width = desc.width;
  cpp.height = desc.height;
  cpp.colorFormat = desc.color_format;
  cpp.depthFormat = desc.depth_format;
  cpp.output = stereo::HostOutput(desc.output);
  cpp.method = toCpp(desc.method);
  cpp.searchTaps = desc.search_taps;
  cpp.iterations = desc.iterations;
  cpp.previousFrameFill = desc.previous_frame_fill != 0;
  cpp.hybridBudget = desc.hybrid_budget;
  cpp.hybridCell = desc.hybrid_cell;
  cpp.hybridScoreFloor = desc.hybrid_score_floor;
  return cpp;
}

s3d::stereo::StereoFrameDispatch checkedDispatch(const s3d::stereo::StereoFrame& f, const s3d_stereo_frame_dispatch& d) {
  const bool hybrid = f.desc().method == s3d::stereo::StereoMethod::Hybrid;
  const char* centerCameraFor = f.desc().previousFrameFill ? "the previous-frame fill"
                                : hybrid                   ? "the hybrid's eye cameras"
                                                           : nullptr;
  s3d::capi::validate(d, f.desc().colorFormat, f.desc().depthFormat, f.eyeFormat(),
                      f.desc().output == s3d::stereo::HostOutput::TwoEyes, centerCameraFor, f.desc().width,
                      f.desc().height);
  s3d::stereo::StereoFrameDispatch cpp;
  cpp.color = toCpp(d.color);
  cpp.depth = toCpp(d.depth);
  cpp.left = toCpp(d.left);
  cpp.right = toCpp(d.right);
  cpp.target = toCpp(d.target);
  cpp.projection = toCpp(d.projection);
  cpp.maxSeparation = d.max_separation;
  cpp.zeroParallaxDistance = d.zero_parallax_distance;
  cpp.edgeCrop = d.edge_crop;
  cpp.weaponDepthOffset = d.weapon_depth_offset;
  cpp.weaponDepthScale = d.weapon_depth_scale;
  cpp.centerView = glm::make_mat4(d.center_view);
  cpp.centerProjection = glm::make_mat4(d.center_projection);
  cpp.cameraCut = d.camera_cut != 0;
  if (d.eye_views) cpp.eyeViews = toCpp(*d.eye_views, f.desc().width, f.desc().height);
  if (hybrid) {
    cpp.leftMask = toCpp(d.left_mask);
    cpp.rightMask = toCpp(d.right_mask);
  }
  return cpp;
}

void requireHybrid(const s3d::stereo::StereoFrame& f, const char* function) {
  if (f.desc().method != s3d::stereo::StereoMethod::Hybrid)
    s3d::capi::fail(std::string(function) + " needs a frame made with S3D_METHOD_HYBRID (s3d_stereo_frame_desc.method)");
}

void toC(const stereo::HybridEyeCameras& eyes, s3d_eye_cameras* cameras) {
  std::memcpy(cameras->left_view, glm::value_ptr(eyes.left.view), sizeof cameras->left_view);
  std::memcpy(cameras->left_projection, glm::value_ptr(eyes.left.projection), sizeof cameras->left_projection);
  std::memcpy(cameras->right_view, glm::value_ptr(eyes.right.view), sizeof cameras->right_view);
  std::memcpy(cameras->right_projection, glm::value_ptr(eyes.right.projection), sizeof cameras->right_projection);
}

}  // namespace s3d::capi

using s3d::capi::checkedDispatch;
using s3d::capi::guarded;
using s3d::capi::present;
using s3d::capi::requireHybrid;
using s3d::capi::requireNotNull;
using s3d::capi::toCpp;

extern "C" {

void s3d_default_stereo_frame_desc(s3d_stereo_frame_desc* out) {
  if (!present(out, "out")) return;
  const s3d::stereo::StereoFrameDesc defaults;
  *out = {0, 0, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_D32_SFLOAT, S3D_OUTPUT_TWO_EYES, S3D_METHOD_SEARCH,
          defaults.searchTaps, defaults.iterations, 0, defaults.hybridBudget, defaults.hybridCell,
          defaults.hybridScoreFloor};
}

void s3d_default_stereo_frame_dispatch(s3d_stereo_frame_dispatch* out) {
  if (!present(out, "out")) return;
  const s3d::stereo::StereoFrameDispatch defaults;
  std::memset(out, 0, sizeof *out);
  out->projection = {defaults.projection.nearPlane, defaults.projection.farPlane, 0, 0, 0.0f,
                     defaults.projection.firstPersonNear, defaults.projection.firstPersonFar};
  out->max_separation = defaults.maxSeparation;
  out->zero_parallax_distance = defaults.zeroParallaxDistance;
  out->edge_crop = defaults.edgeCrop;
  out->weapon_depth_offset = defaults.weaponDepthOffset;
  out->weapon_depth_scale = defaults.weaponDepthScale;
  std::memcpy(out->center_view, glm::value_ptr(defaults.centerView), sizeof out->center_view);
  std::memcpy(out->center_projection, glm::value_ptr(defaults.centerProjection), sizeof out->center_projection);
}

s3d_result s3d_stereo_frame_create(s3d_context context, const s3d_stereo_frame_desc* desc, s3d_stereo_frame* out) {
  return guarded([&] {
    requireNotNull(context, {"context"});
    requireNotNull(desc, {"desc"});
    requireNotNull(out, {"out"});
    const s3d::stereo::StereoFrameDesc cpp = s3d::capi::checkedDesc(*desc, context->maxImageDimension2D);
    *out = new s3d_stereo_frame_t{s3d::stereo::StereoFrame(context->context, cpp)};
  });
}

void s3d_stereo_frame_destroy(s3d_stereo_frame frame) { delete frame; }

s3d_result s3d_stereo_for_eye_views(const s3d_eye_views* views, uint32_t width, uint32_t height,
                                    s3d_eye_views_stereo* out) {
  return guarded([&] {
    requireNotNull(views, {"views"});
    requireNotNull(out, {"out"});
    if (width == 0) s3d::capi::fail("width is 0");
    if (height == 0) s3d::capi::fail("height is 0");
    s3d::capi::validate(*views, width, height, "views->");
    const s3d::stereo::ViewConfiguration cpp = toCpp(*views, width, height);
    const s3d::stereo::CenterView center = s3d::stereo::sharedCenterView(cpp);
    const s3d::stereo::EyeViewsParallax parallax = s3d::stereo::eyeViewsParallax(cpp);
    out->center = {float(0.5 * (cpp.eyes[0].positionX + cpp.eyes[1].positionX)), float(std::atan(center.tanLeft)),
                   float(std::atan(center.tanRight)), float(std::atan(center.tanUp)), float(std::atan(center.tanDown))};
    out->max_separation = parallax.maxSeparation;
    out->zero_parallax_distance = parallax.zeroParallaxDistance;
  });
}

VkFormat s3d_stereo_frame_eye_format(s3d_stereo_frame frame) {
  return present(frame, "frame") ? frame->frame.eyeFormat() : VK_FORMAT_UNDEFINED;
}

void s3d_stereo_frame_packed_size(s3d_stereo_frame frame, uint32_t* width, uint32_t* height) {
  const bool valid = present(frame, "frame");
  if (width) *width = valid ? frame->frame.packedWidth() : 0;
  if (height) *height = valid ? frame->frame.packedHeight() : 0;
}

s3d_result s3d_stereo_frame_record(s3d_stereo_frame frame, VkCommandBuffer cmd,
                                   const s3d_stereo_frame_dispatch* dispatch) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    requireNotNull(dispatch, {"dispatch"});
    if (frame->frame.desc().method == s3d::stereo::StereoMethod::Hybrid)
      s3d::capi::fail("s3d_stereo_frame_record: a S3D_METHOD_HYBRID frame records with "
                      "s3d_stereo_frame_record_hybrid_masks and s3d_stereo_frame_record_hybrid_composite");
    frame->frame.record(cmd, checkedDispatch(frame->frame, *dispatch));
  });
}

s3d_result s3d_stereo_frame_record_hybrid_masks(s3d_stereo_frame frame, VkCommandBuffer cmd,
                                                const s3d_stereo_frame_dispatch* dispatch, s3d_eye_cameras* cameras) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    requireNotNull(dispatch, {"dispatch"});
    requireNotNull(cameras, {"cameras"});
    requireHybrid(frame->frame, "s3d_stereo_frame_record_hybrid_masks");
    s3d::capi::validateHybridMasks(*dispatch);
    s3d::capi::toC(frame->frame.recordHybridMasks(cmd, checkedDispatch(frame->frame, *dispatch)), cameras);
  });
}

s3d_result s3d_stereo_frame_record_hybrid_composite(s3d_stereo_frame frame, VkCommandBuffer cmd,
                                                    const s3d_stereo_frame_dispatch* dispatch) {
  return guarded([&] {
    requireNotNull(frame, {"frame"});
    s3d::capi::requireHandle(cmd, {"cmd"});
    requireNotNull(dispatch, {"dispatch"});
    requireHybrid(frame->frame, "s3d_stereo_frame_record_hybrid_composite");
    frame->frame.recordHybridComposite(cmd, checkedDispatch(frame->frame, *dispatch));
  });
}

}  // extern "C"
