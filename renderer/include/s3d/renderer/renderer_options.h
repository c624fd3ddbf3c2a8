#pragma once
// How a DeferredRenderer renders (fixed at its creation): supersampling, reversed-Z and which implementation
// each pass with two runs.
#include <cstdint>
#include <optional>
#include <string_view>

namespace s3d::renderer {

struct RendererOptions {
  // Supersampling anti-aliasing: every pass before the resolve runs at supersample x the output size; the
  // resolve averages the samples of each output pixel (seed 4.6's "edge sampling" flaw: aliased edges in the
  // center view cannot be displaced by a fraction of a pixel). 1 (default) to 4.
  std::uint32_t supersample = 1;
  // Reversed-Z depth buffer: cleared to 0, depth test GREATER, near and far swapped in both layers'
  // projections (the world in device depth [0, 0.9], first-person in [0.9, 1]). D32 float then keeps its
  // precision at the far end, where standard Z spends it all near 1. Linear depth is the same either way.
  bool reversedZ = false;
  // Tests: every frame counts what its passes shaded (PassTiming::shadedPixels), with atomic adds per pixel.
  bool countShadedPixels = false;
  // How the G-buffer pass gets each pixel's normal and material (the images agree to half-float rounding).
  enum class GBufferShading {
    Automatic,   // Visibility on GPUs, Raster on CPU devices: the faster on each (docs/RESULTS.md, "The G-buffer's raster side")
    Raster,      // the fragment shader evaluates and writes them (a CPU rasterizer interpolates cheaply)
    Visibility,  // fragments write a triangle id only; a compute pass evaluates the surface per pixel (a GPU
                 // whose raster side is a small part of the chip pays per byte a fragment writes)
  };
  GBufferShading gbufferShading = GBufferShading::Automatic;
  // How transparent objects are blended over the lit image (the images agree to half-float rounding and the
  // rare pixel centre on a triangle edge).
  enum class TransparentCompositing {
    Automatic,  // Compute on GPUs, Raster on CPU devices: the faster on each (docs/RESULTS.md, "Transparent pass")
    Raster,     // a blended raster pass: only covered fragments are shaded (cheap on a CPU rasterizer)
    Compute,    // a compute pass per object over the tiles its bounds cover (a GPU whose raster side is a small
                // part of the chip pays per byte a blended fragment reads and writes)
  };
  TransparentCompositing transparentCompositing = TransparentCompositing::Automatic;
};

// "auto", "raster", "visibility"; and back (nullopt for any other name).
const char* gbufferShadingName(RendererOptions::GBufferShading shading);
std::optional<RendererOptions::GBufferShading> gbufferShadingFromName(std::string_view name);

}  // namespace s3d::renderer
