// The C API's stereo frame over stereo::StereoFrame: the C structs checked field by field, then converted on the
// stack (recording allocates nothing).
#include <cmath>
#include <cstring>

#include <glm/gtc/type_ptr.hpp>

#include "capi_common.h"
#include "capi_validate.h"
#include "s3d/stereo/stereo_frame.h"

struct s3d_stereo_frame_t {
  s3d::stereo::StereoFrame frame;
};

namespace {

using s3d::capi::guarded;
using s3d::capi::present;
using s3d::capi::requireNotNull;
using s3d::capi::toCpp;

s3d::stereo::StereoMethod toCpp(s3d_method method) {
  switch (method) {
    case S3D_METHOD_SEED: return s3d::stereo::StereoMethod::Seed;
    case S3D_METHOD_ITERATIVE: return s3d::stereo::StereoMethod::Iterative;
    case S3D_METHOD_FORWARD: return s3d::stereo::StereoMethod::Forward;
    default: return s3d::stereo::StereoMethod::Search;
  }
}

}  // namespace

extern "C" {

void s3d_default_stereo_frame_desc(s3d_stereo_frame_desc* out) {
  if (!present(out, "out")) return;
  const s3d::stereo::StereoFrameDesc defaults;
  *out = {0, 0, VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_D32_SFLOAT, S3D_OUTPUT_TWO_EYES, S3D_METHOD_SEARCH,
          defaults.searchTaps, defaults.iterations, 0};
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
    s3d::capi::validate(*desc, context->maxImageDimension2D);
    s3d::stereo::StereoFrameDesc cpp;
    cpp.width = desc->width;
    cpp.height = desc->height;
    cpp.colorFormat = desc->color_format;
    cpp.depthFormat = desc->depth_format;
    cpp.output = s3d::stereo::HostOutput(desc->output);
    cpp.method = toCpp(desc->method);
    cpp.searchTaps = desc->search_taps;
    cpp.iterations = desc->iterations;
    cpp.previousFrameFill = desc->previous_frame_fill != 0;
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
    const s3d::stereo::StereoFrame& f = frame->frame;
    s3d::capi::validate(*dispatch, f.desc().colorFormat, f.desc().depthFormat, f.eyeFormat(),
                        f.desc().output == s3d::stereo::HostOutput::TwoEyes, f.desc().previousFrameFill,
                        f.desc().width, f.desc().height);
    s3d::stereo::StereoFrameDispatch cpp;
    cpp.color = toCpp(dispatch->color);
    cpp.depth = toCpp(dispatch->depth);
    cpp.left = toCpp(dispatch->left);
    cpp.right = toCpp(dispatch->right);
    cpp.target = toCpp(dispatch->target);
    cpp.projection = toCpp(dispatch->projection);
    cpp.maxSeparation = dispatch->max_separation;
    cpp.zeroParallaxDistance = dispatch->zero_parallax_distance;
    cpp.edgeCrop = dispatch->edge_crop;
    cpp.weaponDepthOffset = dispatch->weapon_depth_offset;
    cpp.weaponDepthScale = dispatch->weapon_depth_scale;
    cpp.centerView = glm::make_mat4(dispatch->center_view);
    cpp.centerProjection = glm::make_mat4(dispatch->center_projection);
    cpp.cameraCut = dispatch->camera_cut != 0;
    if (dispatch->eye_views) cpp.eyeViews = toCpp(*dispatch->eye_views, f.desc().width, f.desc().height);
    frame->frame.record(cmd, cpp);
  });
}

}  // extern "C"
