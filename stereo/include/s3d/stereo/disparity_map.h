#pragma once
// Nonlinear depth-to-parallax mapping: a per-frame monotonic curve over the frame's depth distribution (the
// disparity budget's GPU reduction, depth_range.h), applied to the depth the stereo pass reads
// (disparity_map_shared.h; disparity_map_pass.h on the GPU, mapDepthReference here).
//
// The linear mapping spends the disparity range in proportion to inverse depth: empty depth intervals (the gap
// between the farthest wall and the sky, between the weapon and the room) take as much of the budget as
// populated ones. The nonlinear map gives each interval a share in between its inverse-depth span and its
// share of the pixels (a clamped histogram equalization, in the spirit of Lang et al. 2010's nonlinear disparity
// mapping operators): the populated depths get more disparity, the empty gaps less. Invariants, so
// the disparity budget's fit holds unchanged:
//  - the nearest depth and the farthest shown depth (the sky, or the farthest finite depth) are fixed points:
//    the frame's parallax range is exactly the linear one, every pixel's parallax within it;
//  - the zero-parallax distance is a fixed point when it lies inside the range: no pixel crosses the screen
//    plane (the weapon stays behind it, nothing new pops out);
//  - the curve is strictly increasing: depth order, and so occlusion, is kept.
#include <string>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/depth_range.h"
#include "s3d/stereo/disparity_map_shared.h"
#include "s3d/stereo/stereo.h"  // DisparityMapping

namespace s3d::stereo {

// Share of each interval's disparity given by its pixel count rather than by its inverse-depth span: 0 is the
// linear mapping, values toward 1 equalize more (1 itself could flatten an empty interval to nothing). An
// empty interval keeps 1 - strength of its linear share; a populated one is stretched by at most
// kMaxMappingStretch (a flat far wall that holds half the pixels must not become a deep room).
inline constexpr float kDefaultMappingStrength = 0.5f;
inline constexpr float kMaxMappingStrength = 0.9f;
inline constexpr float kMaxMappingStretch = 4.0f;

// The identity map (the linear mapping).
gpu::DisparityMapConstants identityDisparityMap();

// The frame's curve from its depth range: knots at the fixed points (the sky or farthest depth, the zero-parallax
// distance when inside, the nearest depth), the farthest finite depth, and histogram bin edges at equal shares
// of the finite pixels, up to S3D_DISPARITY_MAP_KNOTS in all. The identity when the range has fewer than two
// distinct depths. Throws std::invalid_argument for a strength outside [0, kMaxMappingStrength] or a
// non-positive zero-parallax distance.
gpu::DisparityMapConstants nonlinearDisparityMap(const DepthRange& range, float zeroParallaxDistance,
                                                 float strength = kDefaultMappingStrength);

// The map `mapping` asks for (the identity for Linear).
gpu::DisparityMapConstants disparityMapFor(DisparityMapping mapping, const DepthRange& range,
                                           float zeroParallaxDistance);

// The C++ reference of DisparityMapPass: every pixel through gpu::mappedDepth.
void mapDepthReference(DepthImage& linearDepth, const gpu::DisparityMapConstants& map);
DepthImage mappedDepthImage(DepthImage linearDepth, const gpu::DisparityMapConstants& map);

// The map as an affine function of inverse depth on each segment between knots, w = intercept + slope u, for
// the per-layer reference (a pair of eye cameras exact for one segment each). Segment i covers [u_i, u_i+1];
// for choosing a layer the first one's interval starts at u = 0 and the last one's ends at +inf (depths the
// center view does not show, seen by an eye only, take the nearest segment's camera). The identity gives one
// segment {0, +inf, slope 1, intercept 0}.
struct DisparityMapSegment {
  double inverseDepthBegin = 0.0, inverseDepthEnd = 0.0;  // [begin, end] in u
  double slope = 1.0, intercept = 0.0;
};
std::vector<DisparityMapSegment> disparityMapSegments(const gpu::DisparityMapConstants& map);

}  // namespace s3d::stereo
