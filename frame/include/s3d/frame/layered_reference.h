#pragma once
// The two-pass reference of an eye, for the linear mapping and for the nonlinear one (disparity_map.h). A pair
// of off-axis eye cameras gives parallax affine in inverse depth, A - B / d, so it reproduces the linear mapping
// exactly but a nonlinear map only on one of its segments. The per-layer reference renders the eye once per
// segment, each with the cameras exact for that segment (stereo::affineInverseDepthTerms), and keeps per pixel
// the nearest surface whose depth lies in its own layer's segment: the nearest surface the mapped frame puts
// there. It is exact wherever that surface is not hidden, in its own layer's rendering, by a nearer surface
// from another segment (near depth edges across segments); pixels where no layer qualifies take the layer whose
// segment lies nearest to their depth and are counted.
#include <cstdint>
#include <optional>
#include <vector>

#include "s3d/image.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"
#include "s3d/stereo/disparity_map.h"
#include "s3d/stereo/stereo.h"

namespace s3d::frame {

// The view of one eye with cameras exact for parallax m (1 - zpp w), w = intercept + slope / d (the identity
// segment: the linear mapping). Both layers get their own off-axis camera: the first-person layer has its own
// projection, and follows the pushed weapon depth (its chord composed with the segment). Its shadow maps are
// planned for the center view's camera (renderer::ViewMatrices::shadowFit), as every view of the stereo frame's.
renderer::ViewMatrices referenceEyeView(const renderer::Scene& scene, const renderer::ViewMatrices& center,
                                        stereo::Eye eye, const stereo::StereoParameters& parameters,
                                        const stereo::DisparityMapSegment& segment = {});

struct ReferenceEye {
  ImageRGBA8 display;
  DepthImage depth;  // linear depth as rendered (weapon pushed), not mapped
  ImageRGBA32F hdr;
  std::vector<std::uint8_t> transparent;
  std::vector<std::uint8_t> foliage;      // the renderer's cut-out mask (readCutoutMask)
  std::vector<std::uint8_t> firstPerson;  // the renderer's first-person (weapon) mask
  // Per pixel the layer (index into disparityMapSegments(map)) whose rendering it shows: all 0 for one layer.
  std::vector<std::uint8_t> layerOfPixel;
  std::uint32_t layers = 1;              // renders it took (the map's segments)
  std::uint64_t unresolvedPixels = 0;    // no layer's surface lay in its own segment
  std::optional<double> firstLayerGpuMs;  // the first layer's whole deferred frame
};

// Renders `eye` with `deferred` (at its size, the center view's frustum `center`) under `map`: one layer for
// the identity, one per segment otherwise. The renderer's images are overwritten.
ReferenceEye renderReferenceEye(renderer::DeferredRenderer& deferred, const renderer::Scene& scene,
                                const renderer::ViewMatrices& center, stereo::Eye eye,
                                const stereo::StereoParameters& parameters, const gpu::DisparityMapConstants& map);

// The per-pixel choice of the per-layer reference, on its own (tests): `layerDepths[k]` is layer k's rendered
// depth; returns per pixel the chosen layer, and counts pixels without a qualifying layer.
std::vector<std::uint8_t> chooseReferenceLayers(const std::vector<DepthImage>& layerDepths,
                                                const std::vector<stereo::DisparityMapSegment>& segments,
                                                std::uint64_t* unresolvedPixels = nullptr);

}  // namespace s3d::frame
