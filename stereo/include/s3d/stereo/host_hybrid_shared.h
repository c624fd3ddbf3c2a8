// The host hybrid's mask as depth (stereo_hybrid_mask_depth.comp, host_hybrid_pass.h): per eye pixel the depth the
// host's raster tests against, far where the mask is set (its fragments pass) and near elsewhere (they fail).
#ifndef S3D_HOST_HYBRID_SHARED_H
#define S3D_HOST_HYBRID_SHARED_H

#include "s3d/gpu/shared.h"

S3D_GPU_BEGIN

#define S3D_HOST_HYBRID_GROUP_SIZE 8  // 8 x 8 workgroups

struct HostHybridDepthConstants {
  int width;
  int height;
  float maskedDepth;    // the host's far value: 1, or 0 with reversed-Z
  float unmaskedDepth;  // the host's near value: 0, or 1 with reversed-Z
};

S3D_GPU_END

#endif  // S3D_HOST_HYBRID_SHARED_H
