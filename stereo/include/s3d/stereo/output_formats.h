#pragma once
// Frame-compatible stereo output: turn a left/right pair of display images into one image that an
// ordinary screen (anaglyph) or a 3D TV / headset player (side-by-side, top-and-bottom) can show.
#include <string_view>

#include "s3d/image.h"

namespace s3d::stereo {

// Red-cyan anaglyph by Dubois' least-squares projection, mixed in linear light.
// Both eyes must have the same size; the result has that size and is fully opaque.
ImageRGBA8 makeAnaglyphDubois(const ImageRGBA8& left, const ImageRGBA8& right);

// Full: each eye keeps its resolution, the frame doubles in one direction.
// Half: the frame keeps the eye resolution, each eye is squeezed to half of it (what most 3D TVs expect).
enum class PackingMode { Half, Full };

// "half" or "full" (exact, lower case); anything else throws std::invalid_argument listing the choices.
PackingMode parsePackingMode(std::string_view name);

// Left eye on the left. Full: 2W x H. Half: W x H, each eye box-filtered horizontally in linear light
// (even W: exactly the average of each pixel pair). Odd W: the left eye gets ceil(W/2) columns and the
// right eye floor(W/2); each eye's whole width is area-averaged into its columns, so no source column is dropped.
ImageRGBA8 makeSideBySide(const ImageRGBA8& left, const ImageRGBA8& right, PackingMode mode);

// Left eye on top. Full: W x 2H. Half: W x H, each eye box-filtered vertically in linear light
// (even H: exactly the average of each row pair). Odd H: the top (left) eye gets ceil(H/2) rows, the
// bottom (right) eye floor(H/2), each eye's whole height area-averaged into its rows.
ImageRGBA8 makeTopAndBottom(const ImageRGBA8& left, const ImageRGBA8& right, PackingMode mode);

}  // namespace s3d::stereo
