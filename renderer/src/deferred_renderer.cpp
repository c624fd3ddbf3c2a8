#include "s3d/renderer/deferred_renderer.h"

#include <algorithm>
#include <array>
#include <functional>
#include <stdexcept>
#include <string>

#include "deferred_renderer_impl.h"

namespace s3d::renderer {

std::vector<DeferredRenderer::Impl::ScheduledPass> DeferredRenderer::Impl::schedulePasses(
    const ViewMatrices& view, const ShadeMask& mask, const detail::ShadowMaps* lentShadows) {
  std::vector<ScheduledPass> passes;
  const bool masked = mask.image != nullptr;
  sortFrontToBack(view);
  const bool withAmbientOcclusion = scene.ambientOcclusion;
  if (masked) {
    passes.push_back({"mask-tiles", [this, mask, resetAhead = tilesResetAhead](VkCommandBuffer cmd) {
                        tiles->recordReset(cmd, frameBuffer.buffer, mask.image, !raycastFrame, resetAhead);
                        tiles->recordBuild(cmd, frameBuffer.buffer, *mask.image);
                      }});
    if (withAmbientOcclusion && !maskedGBufferWritesEveryPixel() && !raycastFrame)
      passes.push_back({"ssao-depth", [this](VkCommandBuffer cmd) { recordAmbientDepth(cmd); }});
  }
  // The G-buffer's count (the render pixels with a surface) comes from the G-buffer resolve, or under raster
  // shading from a counting pass of its own.
  if (raycastFrame)
    passes.push_back({"raycast", [this, view, mask](VkCommandBuffer cmd) {
                        if (mask.image == nullptr) tiles->recordReset(cmd, frameBuffer.buffer, nullptr, false);
                        recordRaycastSurfaces(cmd, view, mask);
                      }});
  else
    passes.push_back({"gbuffer",
                      [this, mask](VkCommandBuffer cmd) {
                        if (mask.image == nullptr) tiles->recordReset(cmd, frameBuffer.buffer, nullptr, true);
                        recordGBuffer(cmd, mask);
                      },
                      S3D_COUNT_GBUFFER});
  if (visibilityShading)
    passes.push_back({"gbuffer-resolve", [this, mask](VkCommandBuffer cmd) { recordGBufferResolve(cmd, mask); }});
  else if (options.countShadedPixels)
    passes.push_back({"gbuffer-count", [this](VkCommandBuffer cmd) {
                        tiles->recordCountGBuffer(cmd, frameBuffer.buffer, materialTarget, nearestSampler);
                      }});
  if (withAmbientOcclusion) {
    const vk::Image& occlusionDepth =
        raycastFrame ? raycastDepth : masked && !maskedGBufferWritesEveryPixel() ? ambientDepth : depth;
    passes.push_back({"ssao",
                      [this, &occlusionDepth, masked](VkCommandBuffer cmd) {
                        ambientOcclusion->recordOcclusion(cmd, occlusionDepth, frameBuffer.buffer, tiles->buffer(), masked);
                      },
                      S3D_COUNT_SSAO});
    passes.push_back({"ssao-blur",
                      [this, masked](VkCommandBuffer cmd) {
                        ambientOcclusion->recordBlur(cmd, frameBuffer.buffer, tiles->buffer(), masked);
                      },
                      S3D_COUNT_SSAO_BLUR});
  }
  if (lentShadows == nullptr)
    for (detail::ShadowPass& shadowPass : shadows->schedule(view))
      passes.push_back({std::move(shadowPass.name), std::move(shadowPass.record)});
  const detail::ShadowMaps* frameShadows = lentShadows != nullptr ? lentShadows : shadows.get();
  lighting->prepareFrame(scene, view, *frameShadows);
  passes.push_back({"lighting",
                    [this, mask, frameShadows](VkCommandBuffer cmd) { recordLighting(cmd, mask, *frameShadows); },
                    S3D_COUNT_LIGHTING});
  const bool withTransparent = transparentPass->hasObjects();
  // Keeps a raster transparent pass within the mask (the compute pass reads the mask itself: cheaper than the
  // full-screen fill, docs/RESULTS.md "What did not work").
  if (withTransparent && masked && maskedGBufferWritesEveryPixel() && !transparentPass->usesCompute())
    passes.push_back({"mask-depth", [this, mask](VkCommandBuffer cmd) {
                        vk::transition(cmd, depth, kComputeSampled, vk::kDepthAttachment);
                        recordMaskDepthFill(cmd, mask, VK_ATTACHMENT_LOAD_OP_LOAD);
                        vk::transition(cmd, depth, vk::kDepthAttachment, kComputeSampled);
                      }});
  if (withTransparent) {
    passes.push_back({"transparent", [this, view, mask](VkCommandBuffer cmd) { recordTransparent(cmd, view, mask); }});
  }
  if (!resolveInLighting())
    passes.push_back({"resolve",
                      [this, mask, withTransparent](VkCommandBuffer cmd) { recordResolve(cmd, mask, withTransparent); },
                      S3D_COUNT_RESOLVE});
  return passes;
}

void DeferredRenderer::Impl::validateMask(const ShadeMask& mask) const {
  if (mask.displayTarget != nullptr &&
      (mask.displayTarget->format != kDisplayFormat || mask.displayTarget->width != outputWidth ||
       mask.displayTarget->height != outputHeight))
    throw std::invalid_argument("renderer: the display target must be an R8G8B8A8_UNORM image of the output's size");
  if (mask.image == nullptr) return;
  if (mask.image->format != VK_FORMAT_R32_UINT)
    throw std::invalid_argument("renderer: the shade mask must be an R32_UINT image");
  if (mask.image->width != outputWidth || mask.image->height != outputHeight)
    throw std::invalid_argument("renderer: the shade mask is " + std::to_string(mask.image->width) + "x" +
                                std::to_string(mask.image->height) + ", the output " + std::to_string(outputWidth) +
                                "x" + std::to_string(outputHeight));
  if (mask.uncastDepth == nullptr) return;
  if (mask.surfaces != ShadeMask::Surfaces::RayCast)
    throw std::invalid_argument("renderer: an uncast depth is for ray-cast surfaces only");
  if (mask.uncastDepth->format != VK_FORMAT_R32_SFLOAT || mask.uncastDepth->width != outputWidth ||
      mask.uncastDepth->height != outputHeight)
    throw std::invalid_argument("renderer: the uncast depth must be an R32_SFLOAT image of the output's size");
}

const detail::ShadowMaps& DeferredRenderer::Impl::lentShadowMaps(const ViewMatrices& view, const Impl& source) const {
  if (&source == this) throw std::invalid_argument("renderer: a renderer cannot be its own shadow source");
  if (source.width != width || source.height != height)
    throw std::invalid_argument("renderer: the shadow source renders " + std::to_string(source.width) + "x" +
                                std::to_string(source.height) + ", this renderer " + std::to_string(width) + "x" +
                                std::to_string(height));
  if (!source.shadows->castsLike(*shadows))
    throw std::invalid_argument("renderer: the shadow source holds another scene's shadows");
  const std::optional<ShadowFit> planned = source.shadows->plannedFit();
  if (!planned) throw std::invalid_argument("renderer: the shadow source has rendered no frame of its scene");
  if (*planned != shadowFitOf(view))
    throw std::invalid_argument("renderer: the shadow source's last frame planned its shadow maps for another camera");
  return *source.shadows;
}

std::vector<DeferredRenderer::Impl::ScheduledPass> DeferredRenderer::Impl::prepareFrame(
    const ViewMatrices& view, const ShadeMask& mask, const Impl* shadowSource) {
  if (meshRanges.empty()) throw std::logic_error("DeferredRenderer::render called before setScene");
  validateMask(mask);
  raycastFrame = mask.surfaces == ShadeMask::Surfaces::RayCast;
  if (raycastFrame) {
    if (const std::optional<std::string> refusal = raycastRefusal()) throw std::invalid_argument("renderer: " + *refusal);
    if (!raycast || !raycastBvhCurrent)
      throw std::invalid_argument("renderer: no BVH was given for scene '" + scene.name + "' (setSurfaceBvh)");
  }
  const detail::ShadowMaps* lentShadows = shadowSource != nullptr ? &lentShadowMaps(view, *shadowSource) : nullptr;
  writeFrameConstants(view, mask);
  std::vector<ScheduledPass> passes = schedulePasses(view, mask, lentShadows);
  tilesResetAhead = false;  // a reset recorded ahead serves the render right after it only
  if (passes.size() > kMaxPasses) throw std::logic_error("renderer: more passes than timestamps");
  return passes;
}

void DeferredRenderer::Impl::recordFrame(VkCommandBuffer cmd, const std::vector<ScheduledPass>& passes) {
  constexpr VkPipelineStageFlags2 kAll = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  timestamps.reset(cmd);
  timestamps.write(cmd, 0, kAll);
  for (std::uint32_t pass = 0; pass < passes.size(); ++pass) {
    passes[pass].record(cmd);
    timestamps.write(cmd, pass + 1, kAll);
  }
  if (options.countShadedPixels) tiles->recordCountReadback(cmd);
}

FrameTimings DeferredRenderer::Impl::frameTimings(const std::vector<ScheduledPass>& passes) const {
  FrameTimings timings;
  const auto passCount = std::uint32_t(passes.size());
  timings.totalGpuMs = timestamps.elapsedMs(0, passCount);
  const std::array<std::uint32_t, S3D_COUNT_SLOTS> counts =
      options.countShadedPixels ? tiles->readCounts() : std::array<std::uint32_t, S3D_COUNT_SLOTS>{};
  for (std::uint32_t pass = 0; pass < passCount; ++pass) {
    PassTiming timing{passes[pass].name, timestamps.elapsedMs(pass, pass + 1).value_or(0.0), std::nullopt};
    if (options.countShadedPixels && passes[pass].counterSlot >= 0)
      timing.shadedPixels = counts[std::size_t(passes[pass].counterSlot)];
    timings.passes.push_back(timing);
  }
  return timings;
}

FrameTimings DeferredRenderer::Impl::render(const ViewMatrices& view, const ShadeMask& mask, const Impl* shadowSource) {
  const std::vector<ScheduledPass> passes = prepareFrame(view, mask, shadowSource);
  context.submitAndWait([&](VkCommandBuffer cmd) { recordFrame(cmd, passes); });
  return frameTimings(passes);
}

ConcurrentTimings DeferredRenderer::renderConcurrently(std::span<const ConcurrentView> views) {
  if (views.empty()) return {};
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (views[i].renderer == nullptr) throw std::invalid_argument("renderer: a concurrent view has no renderer");
    if (&views[i].renderer->impl_->context != &views[0].renderer->impl_->context)
      throw std::invalid_argument("renderer: concurrent views' renderers must share one context");
    for (std::size_t j = 0; j < views.size(); ++j)
      if ((j != i && views[j].renderer == views[i].renderer) || views[j].shadowSource == views[i].renderer)
        throw std::invalid_argument("renderer: a renderer of a concurrent view renders only that view and lends it no shadows");
  }
  std::vector<std::vector<Impl::ScheduledPass>> passes;
  for (const ConcurrentView& v : views)
    passes.push_back(v.renderer->impl_->prepareFrame(v.view, v.mask, v.shadowSource ? v.shadowSource->impl_.get() : nullptr));
  // A ray-cast frame lit with lent shadow maps records compute and transfer work only: it may run on the compute
  // queue. Any other frame after the first makes the call submit every view on the main queue, in turn.
  bool restComputeOnly = true;
  for (std::size_t i = 1; i < views.size(); ++i)
    restComputeOnly = restComputeOnly && views[i].renderer->impl_->raycastFrame && views[i].shadowSource != nullptr;
  vk::Context& context = views[0].renderer->impl_->context;
  if (restComputeOnly) {
    std::vector<std::function<void(VkCommandBuffer)>> records;
    for (std::size_t i = 0; i < views.size(); ++i)
      records.push_back([&, i](VkCommandBuffer cmd) { views[i].renderer->impl_->recordFrame(cmd, passes[i]); });
    context.submitConcurrentlyAndWait(records);
  } else {
    context.submitAndWait([&](VkCommandBuffer cmd) {
      for (std::size_t i = 0; i < views.size(); ++i) views[i].renderer->impl_->recordFrame(cmd, passes[i]);
    });
  }
  ConcurrentTimings timings;
  std::optional<std::uint64_t> first, last;
  double longest = 0.0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const Impl& r = *views[i].renderer->impl_;
    timings.views.push_back(r.frameTimings(passes[i]));
    longest = std::max(longest, timings.views.back().totalGpuMs.value_or(0.0));
    const std::optional<std::uint64_t> begin = r.timestamps.ticks(0), end = r.timestamps.ticks(std::uint32_t(passes[i].size()));
    if (!begin || !end) continue;
    first = first ? std::min(*first, *begin) : *begin;
    last = last ? std::max(*last, *end) : *end;
  }
  // Ticks from two queues compare on one device clock (vk::TimestampQueries::ticks); a span shorter than one of
  // its views would show they do not, and is left empty rather than reported.
  if (first && last) {
    const double span = double(std::int64_t(*last - *first)) * context.timestampPeriodNs() * 1e-6;
    if (span >= longest * 0.999) timings.spanGpuMs = span;
  }
  return timings;
}

DeferredRenderer::DeferredRenderer(vk::Context& context, std::uint32_t width, std::uint32_t height,
                                   RendererOptions options)
    : impl_(std::make_unique<Impl>(context, width, height, options)) {}
DeferredRenderer::~DeferredRenderer() = default;

void DeferredRenderer::setScene(const Scene& scene) { impl_->setScene(scene); }
void DeferredRenderer::updateGeometry(const Scene& scene) { impl_->updateGeometry(scene); }
FrameTimings DeferredRenderer::render(const ViewMatrices& view, const ShadeMask& mask) {
  return impl_->render(view, mask, nullptr);
}
FrameTimings DeferredRenderer::render(const ViewMatrices& view, const ShadeMask& mask,
                                      const DeferredRenderer& shadowSource) {
  return impl_->render(view, mask, shadowSource.impl_.get());
}
std::uint32_t DeferredRenderer::width() const { return impl_->outputWidth; }
std::uint32_t DeferredRenderer::height() const { return impl_->outputHeight; }
std::uint32_t DeferredRenderer::supersample() const { return impl_->supersample; }
const RendererOptions& DeferredRenderer::options() const { return impl_->options; }
RendererOptions::GBufferShading DeferredRenderer::gbufferShading() const {
  return impl_->visibilityShading ? RendererOptions::GBufferShading::Visibility : RendererOptions::GBufferShading::Raster;
}

const char* gbufferShadingName(RendererOptions::GBufferShading shading) {
  switch (shading) {
    case RendererOptions::GBufferShading::Raster: return "raster";
    case RendererOptions::GBufferShading::Visibility: return "visibility";
    default: return "auto";
  }
}

std::optional<RendererOptions::GBufferShading> gbufferShadingFromName(std::string_view name) {
  for (auto shading : {RendererOptions::GBufferShading::Automatic, RendererOptions::GBufferShading::Raster,
                       RendererOptions::GBufferShading::Visibility})
    if (name == gbufferShadingName(shading)) return shading;
  return std::nullopt;
}
const vk::Image& DeferredRenderer::displayColor() const { return impl_->display; }
const vk::Image& DeferredRenderer::linearDepth() const { return impl_->linearDepth; }
const vk::Image& DeferredRenderer::deviceDepth() const { return impl_->frameDepth(); }
const vk::Image& DeferredRenderer::hdrColor() const { return impl_->resolvedHdr; }

}  // namespace s3d::renderer
