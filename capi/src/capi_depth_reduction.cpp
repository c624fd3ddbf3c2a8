// The C API's depth reduction: stereo::DepthRangePass on the host's own depth buffer.
#include <vector>

#include "capi_common.h"
#include "s3d/s3d.h"
#include "s3d/stereo/depth_range_pass.h"

struct s3d_depth_reduction_t {
  s3d::stereo::DepthRangePass pass;
  std::vector<std::uint32_t> histogram;  // the last result's bins, what s3d_depth_range::histogram points to
};

using s3d::capi::guarded;
using s3d::capi::requireNotNull;
using s3d::capi::toCpp;

s3d_result s3d_depth_reduction_create(s3d_context context, s3d_depth_reduction* out) {
  return guarded([&] {
    requireNotNull(context, {"context"});
    requireNotNull(out, {"out"});
    *out = new s3d_depth_reduction_t{s3d::stereo::DepthRangePass(context->context), {}};
  });
}

void s3d_depth_reduction_destroy(s3d_depth_reduction reduction) { delete reduction; }

s3d_result s3d_depth_reduction_record(s3d_depth_reduction reduction, VkCommandBuffer cmd, const s3d_host_image* depth,
                                      uint32_t width, uint32_t height, const s3d_projection* projection,
                                      float weapon_depth_offset, float weapon_depth_scale) {
  return guarded([&] {
    requireNotNull(reduction, {"reduction"});
    requireNotNull(cmd, {"cmd"});
    requireNotNull(depth, {"depth"});
    requireNotNull(projection, {"projection"});
    reduction->pass.recordHost(cmd, toCpp(*depth), width, height, toCpp(*projection), weapon_depth_offset,
                               weapon_depth_scale);
  });
}

s3d_result s3d_depth_reduction_result(s3d_depth_reduction reduction, s3d_depth_range* out) {
  return guarded([&] {
    requireNotNull(reduction, {"reduction"});
    requireNotNull(out, {"out"});
    const s3d::stereo::DepthRange range = reduction->pass.result();
    reduction->histogram = range.bins;
    out->nearest = range.nearest;
    out->farthest = range.farthest;
    out->sky_pixels = range.skyPixels;
    out->histogram = reduction->histogram.data();
    out->histogram_bins = std::uint32_t(reduction->histogram.size());
  });
}
