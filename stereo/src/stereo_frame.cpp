#include "s3d/stereo/stereo_frame.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "s3d/number_text.h"
#include "s3d/stereo/forward.h"
#include "s3d/stereo/iterative.h"
#include "s3d/stereo/reprojection.h"

namespace s3d::stereo {
namespace {

[[noreturn]] void refuse(const std::string& field, const std::string& why) {
  throw std::invalid_argument(field + " " + why);
}

bool isHdr(VkFormat format) {
  return format == VK_FORMAT_R16G16B16A16_SFLOAT || format == VK_FORMAT_B10G11R11_UFLOAT_PACK32;
}

// The stereo parameters of a description and a frame's dispatch.
StereoParameters parametersOf(const StereoFrameDesc& desc, const StereoFrameDispatch& dispatch) {
  StereoParameters p;
  p.method = desc.method;
  p.searchTaps = desc.searchTaps;
  p.iterations = desc.iterations;
  p.kernel = desc.kernel;
  p.previousFrameFill = desc.previousFrameFill;
  p.hybridBase = StereoMethod::Search;
  p.hybridBudget = desc.hybridBudget;
  p.hybridCell = desc.hybridCell;
  p.hybridScoreFloor = desc.hybridScoreFloor;
  p.maxSeparation = dispatch.maxSeparation;
  p.zeroParallaxDistance = dispatch.zeroParallaxDistance;
  if (dispatch.eyeViews) {  // checked by record() first
    const EyeViewsParallax parallax = eyeViewsParallax(*dispatch.eyeViews);
    p.maxSeparation = parallax.maxSeparation;
    p.zeroParallaxDistance = parallax.zeroParallaxDistance;
  }
  p.edgeCrop = dispatch.edgeCrop;
  p.weaponDepthOffset = dispatch.weaponDepthOffset;
  p.weaponDepthScale = dispatch.weaponDepthScale;
  return p;
}

// The description's rules: the frame's own, then the method's (stereo::validate, named as description fields);
// formats and sizes are the host pass's (its constructor names them).
const StereoFrameDesc& checked(const StereoFrameDesc& desc) {
  if (desc.method == StereoMethod::Hybrid && desc.output != HostOutput::TwoEyes)
    refuse("StereoFrameDesc.output", "must be two eyes for hybrid: the host draws into the eye images");
  if (isHdr(desc.colorFormat) && desc.method != StereoMethod::Seed && desc.method != StereoMethod::Search)
    refuse("StereoFrameDesc.method", std::string(methodName(desc.method)) + " displaces 8-bit display colour; with HDR "
                                     "colour (RGBA16F, B10G11R11) use seed or search");
  try {
    validate(parametersOf(desc, StereoFrameDispatch{}));
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("StereoFrameDesc.") + error.what());
  }
  return desc;
}

HostStereoPassDesc hostDesc(const StereoFrameDesc& desc) {
  HostStereoPassDesc host;
  host.width = desc.width;
  host.height = desc.height;
  host.colorFormat = desc.colorFormat;
  host.depthFormat = desc.depthFormat;
  host.output = desc.output;
  return host;
}

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Any of the passes below as HostStereoPass's kernel.
template <typename Record>
struct KernelOf final : EyeKernel {
  explicit KernelOf(Record record) : record_(record) {}
  void recordKernel(VkCommandBuffer cmd, const vk::Image& centerColor, const vk::Image& linearDepth,
                    const vk::Image& leftEye, const vk::Image& rightEye) const override {
    record_(cmd, centerColor, linearDepth, leftEye, rightEye);
  }
  Record record_;
};

}  // namespace

StereoFrame::StereoFrame(vk::Context& context, const StereoFrameDesc& desc)
    : desc_(checked(desc)), host_(context, hostDesc(desc)) {
  if (desc.method == StereoMethod::Iterative) iterative_.emplace(context, desc.kernel);
  if (desc.method == StereoMethod::Forward)
    forward_.emplace(context, desc.kernel, desc.previousFrameFill ? ForwardKeys::Kept : ForwardKeys::Discarded);
  if (desc.previousFrameFill) fill_.emplace(context);
  if (desc.method == StereoMethod::Hybrid)
    hybrid_.emplace(context, desc.width, desc.height, desc.kernel,
                    hybridCellFor(parametersOf(desc, StereoFrameDispatch{}), desc.width));
  if (!iterative_ && !forward_ && !hybrid_) return;
  // The passes make their pipelines, z-buffers and history at their first record: one here, so record()
  // allocates nothing.
  const auto image = [&](VkFormat format) {
    return vk::createImage(context, format, desc.width, desc.height, VK_IMAGE_USAGE_STORAGE_BIT);
  };
  const vk::Image color = image(VK_FORMAT_R8G8B8A8_UNORM), depth = image(VK_FORMAT_R32_SFLOAT);
  const vk::Image left = image(VK_FORMAT_R8G8B8A8_UNORM), right = image(VK_FORMAT_R8G8B8A8_UNORM);
  StereoFrameDispatch first;
  context.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* i : {&color, &depth}) vk::transition(cmd, *i, vk::kUndefined, vk::kComputeRead);
    for (const vk::Image* i : {&left, &right}) vk::transition(cmd, *i, vk::kUndefined, vk::kComputeWrite);
    if (hybrid_) hybrid_->recordKernel(cmd, color, depth, left, right, parameters(first), false);
    else recordKernel(cmd, first, color, depth, left, right);
  });
  if (fill_) fill_->reset();
  hasPrevious_ = false;
}

VkFormat StereoFrame::eyeFormat() const { return host_.eyeFormat(); }
std::uint32_t StereoFrame::packedWidth() const { return host_.packedWidth(); }
std::uint32_t StereoFrame::packedHeight() const { return host_.packedHeight(); }

StereoParameters StereoFrame::parameters(const StereoFrameDispatch& dispatch) const {
  return parametersOf(desc_, dispatch);
}

void StereoFrame::recordKernel(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch, const vk::Image& color,
                               const vk::Image& depth, const vk::Image& left, const vk::Image& right) {
  const StereoParameters p = parameters(dispatch);
  if (iterative_) {
    iterative_->record(cmd, color, depth, left, right, makeIterativeConstants(p, p.iterations, desc_.width, desc_.height));
    return;
  }
  const gpu::ForwardConstants constants = makeForwardConstants(p, desc_.width, desc_.height);
  forward_->record(cmd, color, depth, left, right, constants);
  if (!fill_) return;
  // Each eye's camera now and a frame ago (the exact off-axis cameras of the two-pass reference).
  std::array<gpu::EyeMotion, 2> motion{};
  const bool continues = hasPrevious_ && !dispatch.cameraCut;
  if (!continues) fill_->reset();
  for (std::size_t e = 0; e < 2; ++e) {
    const EyeCamera eye = offAxisEyeCamera(dispatch.centerView, dispatch.centerProjection, e == 0 ? Eye::Left : Eye::Right,
                                           p.maxSeparation, p.zeroParallaxDistance);
    motion[e] = continues ? eyeMotion(eye.view, eye.projection, previousEyeView_[e], previousEyeProjection_[e])
                          : staticEyeMotion(eye.projection);
    previousEyeView_[e] = eye.view;
    previousEyeProjection_[e] = eye.projection;
  }
  fill_->record(cmd, *forward_, left, right, constants, motion);
}

void StereoFrame::requireImages(const StereoFrameDispatch& dispatch) const {
  const auto require = [](const HostImage& image, const char* field, VkFormat format, const char* formatName) {
    if (!image.image || !image.view) refuse(std::string("StereoFrameDispatch.") + field, "has no image or view");
    if (image.format != format)
      refuse(std::string("StereoFrameDispatch.") + field + ".format",
             std::to_string(int(image.format)) + " is not " + formatName + " (" + std::to_string(int(format)) + ")");
  };
  require(dispatch.color, "color", desc_.colorFormat, "the description's colorFormat");
  require(dispatch.depth, "depth", desc_.depthFormat, "the description's depthFormat");
  if (desc_.output == HostOutput::TwoEyes) {
    require(dispatch.left, "left", eyeFormat(), "eyeFormat()");
    require(dispatch.right, "right", eyeFormat(), "eyeFormat()");
    if (dispatch.left.image == dispatch.right.image && dispatch.left.layer == dispatch.right.layer)
      refuse("StereoFrameDispatch.right", "names the left eye's image and layer");
  } else {
    require(dispatch.target, "target", eyeFormat(), "eyeFormat()");
  }
}

void StereoFrame::requireCenterCamera(const StereoFrameDispatch& dispatch, const char* forWhat) const {
  if (!finite(dispatch.centerView) || !finite(dispatch.centerProjection) ||
      !(dispatch.centerProjection[0][0] > 0.0f) || dispatch.centerProjection[2][3] == 0.0f)
    refuse("StereoFrameDispatch.centerView/centerProjection",
           std::string("must be finite, with a perspective projection, for ") + forWhat + " (P00 " +
               numberText(dispatch.centerProjection[0][0]) + ")");
}

HostFrame StereoFrame::checkedFrame(const StereoFrameDispatch& dispatch) const {
  if (dispatch.eyeViews)
    if (const std::optional<EyeViewsProblem> found = eyeViewsProblem(*dispatch.eyeViews, desc_.width, desc_.height))
      refuse("StereoFrameDispatch.eyeViews." + fieldName(*found), found->problem);
  const StereoParameters p = parameters(dispatch);
  validate(p);  // names maxSeparation, zeroParallaxDistance, edgeCrop or the weapon push when out of range
  requireImages(dispatch);
  HostFrame frame;
  frame.stereo = desc_.method == StereoMethod::Seed || desc_.method == StereoMethod::Search
                     ? makeStereoConstants(p, desc_.width, desc_.height)
                     : makeSeedConstants(p, desc_.width, desc_.height);  // unused by the other kernels; valid
  frame.projection = dispatch.projection;
  frame.weaponDepthOffset = dispatch.weaponDepthOffset;
  frame.weaponDepthScale = dispatch.weaponDepthScale;
  return frame;
}

void StereoFrame::record(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch) {
  if (hybrid_)
    refuse("StereoFrameDesc.method", "hybrid records in two steps around the host's draw: recordHybridMasks, then "
                                     "recordHybridComposite");
  const HostFrame frame = checkedFrame(dispatch);
  if (fill_) requireCenterCamera(dispatch, "the previous-frame fill");
  const bool eyes = desc_.output == HostOutput::TwoEyes;
  const HostImage* left = eyes ? &dispatch.left : nullptr;
  const HostImage* right = eyes ? &dispatch.right : nullptr;
  const HostImage* target = eyes ? nullptr : &dispatch.target;
  if (!iterative_ && !forward_) {
    host_.record(cmd, dispatch.color, dispatch.depth, frame, left, right, target, dispatch.overlay);
    return;
  }
  const auto run = [&](VkCommandBuffer c, const vk::Image& color, const vk::Image& depth, const vk::Image& l,
                       const vk::Image& r) { recordKernel(c, dispatch, color, depth, l, r); };
  const KernelOf<decltype(run)> kernel(run);
  host_.record(cmd, dispatch.color, dispatch.depth, frame, left, right, target, dispatch.overlay, &kernel);
  if (fill_) fill_->advance();
  hasPrevious_ = true;
}

}  // namespace s3d::stereo

namespace s3d::stereo {

void StereoFrame::requireHybrid(const char* step) const {
  if (!hybrid_)
    refuse("StereoFrameDesc.method", std::string(methodName(desc_.method)) + " records with record(); " + step +
                                         " is the hybrid's");
}

HybridEyeCameras StereoFrame::recordHybridMasks(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch) {
  requireHybrid("recordHybridMasks");
  const HostFrame frame = checkedFrame(dispatch);
  requireCenterCamera(dispatch, "the hybrid's eye cameras");
  const auto requireMask = [&](const HostImage& mask, const char* field) {
    const std::string name = std::string("StereoFrameDispatch.") + field;
    if (!mask.image) refuse(name, "has no image: the hybrid writes each eye's mask into a D32_SFLOAT depth image");
    if (mask.format != VK_FORMAT_D32_SFLOAT)
      refuse(name + ".format", std::to_string(int(mask.format)) + " is not VK_FORMAT_D32_SFLOAT");
    if (mask.layout == VK_IMAGE_LAYOUT_UNDEFINED || mask.layout == VK_IMAGE_LAYOUT_PREINITIALIZED)
      refuse(name + ".layout", "must be the layout the image is in, which it is left in (not UNDEFINED)");
    if (mask.stage == VK_PIPELINE_STAGE_2_NONE && mask.layout != VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL &&
        mask.layout != VK_IMAGE_LAYOUT_GENERAL)
      refuse(name + ".layout", "must be TRANSFER_DST_OPTIMAL or GENERAL when the host synchronizes it (stage 0)");
  };
  requireMask(dispatch.leftMask, "leftMask");
  requireMask(dispatch.rightMask, "rightMask");
  if (dispatch.leftMask.image == dispatch.rightMask.image && dispatch.leftMask.layer == dispatch.rightMask.layer)
    refuse("StereoFrameDispatch.rightMask", "names the left mask's image and layer");
  const StereoParameters p = parameters(dispatch);
  const bool reversedZ = dispatch.projection.reversedZ;
  const auto run = [&](VkCommandBuffer c, const vk::Image& color, const vk::Image& depth, const vk::Image& l,
                       const vk::Image& r) { hybrid_->recordKernel(c, color, depth, l, r, p, reversedZ); };
  const KernelOf<decltype(run)> kernel(run);
  host_.record(cmd, dispatch.color, dispatch.depth, frame, &dispatch.left, &dispatch.right, nullptr, nullptr, &kernel);
  hybrid_->recordMaskCopies(cmd, dispatch.leftMask, dispatch.rightMask);
  const auto camera = [&](Eye eye) {
    return offAxisEyeCamera(dispatch.centerView, dispatch.centerProjection, eye, p.maxSeparation, p.zeroParallaxDistance);
  };
  return {camera(Eye::Left), camera(Eye::Right)};
}

void StereoFrame::recordHybridComposite(VkCommandBuffer cmd, const StereoFrameDispatch& dispatch) const {
  requireHybrid("recordHybridComposite");
  requireImages(dispatch);
  if (!dispatch.overlay) return;
  // The overlay draws on the eyes as the host's draw left them, in GENERAL.
  constexpr vk::ImageState kOverlay{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                    VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  std::array<vk::Image, 2> eyes;
  const HostImage* hosts[] = {&dispatch.left, &dispatch.right};
  for (std::size_t e = 0; e < 2; ++e) {
    eyes[e] = vk::borrowImage(hosts[e]->image, hosts[e]->view, hosts[e]->format, desc_.width, desc_.height,
                              hosts[e]->layer);
    if (hosts[e]->stage != VK_PIPELINE_STAGE_2_NONE)
      vk::transition(cmd, eyes[e], {hosts[e]->layout, hosts[e]->stage, hosts[e]->access}, kOverlay);
  }
  const auto general = [](const HostImage& host) {
    HostImage eye = host;
    eye.layout = VK_IMAGE_LAYOUT_GENERAL;
    eye.stage = VK_PIPELINE_STAGE_2_NONE;
    eye.access = VK_ACCESS_2_NONE;
    return eye;
  };
  dispatch.overlay->recordOnEyes(cmd, general(dispatch.left), general(dispatch.right));
  for (std::size_t e = 0; e < 2; ++e)
    if (hosts[e]->stage != VK_PIPELINE_STAGE_2_NONE)
      vk::transition(cmd, eyes[e], kOverlay, {hosts[e]->layout, hosts[e]->stage, hosts[e]->access});
}

}  // namespace s3d::stereo
