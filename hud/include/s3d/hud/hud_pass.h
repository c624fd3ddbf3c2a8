#pragma once
// The HUD as a GPU pass a host records into its own command buffer (seed 4.6.2): each element layer is blended
// over both eyes at the parallax of its depth, fading where the weapon mask (the eyes' alpha) covers an element
// behind the weapon. Same layers, origins and per-pixel math as the C++ reference (hud_layers.h, compositeHud).
// docs/INTEGRATION.md has the call sequence and the synchronization contract.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "s3d/hud/hud_layers.h"
#include "s3d/hud/hud_pass_shared.h"  // S3D_HUD_MAX_ELEMENTS
#include "s3d/stereo/host_stereo_pass.h"
#include "s3d/vk/context.h"
#include "s3d/vk/pipeline.h"
#include "s3d/vk/resources.h"

namespace s3d::hud {

// One element of the pass, fixed at construction: either s3d's own copy of a layer (uploaded once: the built-in
// panels and crosshair, or any static art of the host's) or the host's image, given to every record() (a layer the
// host redraws, e.g. text that changes).
struct HudPassElement {
  std::string name;
  HudPlacement placement;
  ImageRGBA8 pixels;                    // uploaded at construction; empty for a host layer
  std::uint32_t hostWidth = 0;          // a host layer's size (its image must have exactly this size)
  std::uint32_t hostHeight = 0;

  static HudPassElement uploaded(const HudLayer& layer) { return {layer.name, layer.placement, layer.pixels, 0, 0}; }
  static HudPassElement hostLayer(std::string name, std::uint32_t width, std::uint32_t height, HudPlacement placement) {
    return {std::move(name), placement, ImageRGBA8(), width, height};
  }
  bool isHostLayer() const { return pixels.pixels.empty(); }
};

struct HudPassDesc {
  std::uint32_t width = 0;   // the eyes
  std::uint32_t height = 0;
  std::vector<HudPassElement> elements;  // drawn in this order (later on top); at most S3D_HUD_MAX_ELEMENTS
};

class HudPass;

// The pass bound to one frame's element states, for HostStereoPass::record (the HUD drawn into the pass's own eyes
// before they are packed into a side-by-side, top-bottom or anaglyph target). Holds references: keep `pass`,
// `frames` and `hostLayers` alive until record() returns.
class HudOverlay final : public stereo::EyeOverlay {
 public:
  HudOverlay(const HudPass& pass, std::span<const HudElementFrame> frames, std::span<const stereo::HostImage> hostLayers)
      : pass_(&pass), frames_(frames), hostLayers_(hostLayers) {}
  void recordOnEyes(VkCommandBuffer cmd, const stereo::HostImage& left, const stereo::HostImage& right) const override;

 private:
  const HudPass* pass_;
  std::span<const HudElementFrame> frames_;
  std::span<const stereo::HostImage> hostLayers_;
};

class HudPass {
 public:
  // Creates the pipeline and sampler and uploads s3d's layers (one submit on the context's queue, waited for).
  // Throws std::invalid_argument naming the element for an empty layer, a host layer without a size, or more than
  // S3D_HUD_MAX_ELEMENTS elements.
  HudPass(vk::Context& context, const HudPassDesc& desc);

  // Blends every element that is not hidden over both eyes, in order. `frames`: one per element (parallax and fade
  // from comfort::frameComfortState's HudElementState). `hostLayers`: the host layers' images in element order,
  // R8G8B8A8_UNORM or B8G8R8A8_UNORM (straight alpha), sampled. Eyes: R8G8B8A8_UNORM storage images of the pass's
  // size whose alpha is the weapon mask (0 on the weapon, 255 elsewhere; left as it is). Images with a stage get
  // barriers into the layout s3d needs and back (HostStereoPass's contract); stage NONE: the host has done it.
  // No submit, no wait, no allocation.
  void record(VkCommandBuffer cmd, std::span<const HudElementFrame> frames, std::span<const stereo::HostImage> hostLayers,
              const stereo::HostImage& left, const stereo::HostImage& right) const;

  HudOverlay overlay(std::span<const HudElementFrame> frames, std::span<const stereo::HostImage> hostLayers = {}) const {
    return HudOverlay(*this, frames, hostLayers);
  }

  const HudPassDesc& desc() const { return desc_; }
  std::size_t hostLayerCount() const { return hostLayerCount_; }
  static constexpr VkFormat eyeFormat() { return VK_FORMAT_R8G8B8A8_UNORM; }

 private:
  vk::Context* context_;
  HudPassDesc desc_;
  std::size_t hostLayerCount_ = 0;
  vk::PipelineLayout layout_;
  vk::Unique<VkPipeline> pipeline_;
  vk::Unique<VkSampler> sampler_;
  std::vector<std::optional<vk::Image>> uploaded_;  // per element: s3d's copy of its layer (none for host layers)

  // record()'s arguments checked against the description; returns each host layer's layout while s3d samples it.
  std::array<VkImageLayout, S3D_HUD_MAX_ELEMENTS> checkedLayerLayouts(std::span<const HudElementFrame> frames,
                                                                      std::span<const stereo::HostImage> hostLayers,
                                                                      const stereo::HostImage& left,
                                                                      const stereo::HostImage& right) const;
};

}  // namespace s3d::hud
