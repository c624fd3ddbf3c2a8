// DeferredRenderer's readbacks: the display colour, linear depth, HDR colour, the visibility ids and the masks of
// first-person, transparent and cut-out pixels.
#include <algorithm>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "deferred_renderer_impl.h"

namespace s3d::renderer {

ImageRGBA8 DeferredRenderer::readDisplayColor() {
  ImageRGBA8 image(impl_->outputWidth, impl_->outputHeight);
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->display, vk::kComputeWrite);
  std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
  return image;
}

DepthImage DeferredRenderer::readLinearDepth() {
  DepthImage image(impl_->outputWidth, impl_->outputHeight);
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->linearDepth, vk::kComputeWrite);
  std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
  return image;
}

std::vector<std::uint8_t> DeferredRenderer::readFirstPersonMask() {
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->frameDepth(), kComputeSampled);
  std::vector<float> deviceDepth(bytes.size() / sizeof(float));
  std::memcpy(deviceDepth.data(), bytes.data(), bytes.size());
  const Impl& r = *impl_;
  const bool reversed = r.options.reversedZ;
  std::vector<std::uint8_t> mask(std::size_t(r.outputWidth) * r.outputHeight, 0);
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) {
      const float device = deviceDepth[std::size_t(y) * r.width + x];
      if (reversed ? device >= 1.0f - kFirstPersonDeviceDepthMax : device <= kFirstPersonDeviceDepthMax)
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
    }
  return mask;
}

std::vector<std::uint8_t> DeferredRenderer::readTransparentMask() {
  const Impl& r = *impl_;
  std::vector<std::uint8_t> mask(std::size_t(r.outputWidth) * r.outputHeight, 0);
  if (!r.transparentPass->hasObjects()) return mask;  // the transparent pass did not run
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, r.transparentPass->coverage(),
                                                   r.transparentPass->coverageState());
  // With supersampling, an output pixel is transparent where any of its samples is.
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x)
      if (bytes[4 * (std::size_t(y) * r.width + x)] != std::byte{0})
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
  return mask;
}

std::vector<std::uint8_t> DeferredRenderer::readCutoutMask() {
  const Impl& r = *impl_;
  std::vector<std::uint8_t> mask(std::size_t(r.outputWidth) * r.outputHeight, 0);
  std::vector<bool> cutout(r.scene.objects.size());
  for (std::size_t i = 0; i < cutout.size(); ++i) cutout[i] = r.scene.objects[i].material.isCutout();
  if (std::find(cutout.begin(), cutout.end(), true) == cutout.end()) return mask;
  // The G-buffer's material target names each render pixel's object (S3D_NO_OBJECT for the sky).
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, r.materialTarget, kComputeSampled);
  std::vector<glm::uvec2> material(bytes.size() / sizeof(glm::uvec2));
  std::memcpy(material.data(), bytes.data(), bytes.size());
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) {
      const std::uint32_t object = gpu::unpackObjectIndex(material[std::size_t(y) * r.width + x]);
      if (object < cutout.size() && cutout[object])
        mask[std::size_t(y / r.supersample) * r.outputWidth + x / r.supersample] = 1;
    }
  return mask;
}

std::vector<std::uint32_t> DeferredRenderer::readVisibilityIds() {
  const Impl& r = *impl_;
  if (!r.visibilityShading || r.frameVisibility().format != kNarrowVisibilityFormat) return {};
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, r.frameVisibility(), kComputeSampled);
  std::vector<std::uint32_t> ids(bytes.size() / sizeof(std::uint32_t));
  std::memcpy(ids.data(), bytes.data(), bytes.size());
  return ids;
}

ImageRGBA32F DeferredRenderer::readHdrColor() {
  // The shading target holds half floats; the exposure is applied here so center.exr matches the display.
  std::vector<std::byte> bytes = vk::readbackImage(impl_->context, impl_->resolvedHdr, vk::kComputeWrite);
  ImageRGBA32F image(impl_->outputWidth, impl_->outputHeight);
  std::vector<std::uint16_t> halves(bytes.size() / 2);
  std::memcpy(halves.data(), bytes.data(), bytes.size());
  for (std::size_t i = 0; i < halves.size(); ++i) {
    float value = glm::unpackHalf1x16(halves[i]);
    image.pixels[i] = (i % 4 == 3) ? value : value * impl_->scene.exposure;
  }
  return image;
}

}  // namespace s3d::renderer
