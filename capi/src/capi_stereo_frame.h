#pragma once
// The stereo frame's C structs as StereoFrame takes them, checked field by field (shared by the stereo frame and
// the host comfort frame).
#include <cstdint>

#include "s3d/s3d.h"
#include "s3d/stereo/stereo_frame.h"

namespace s3d::capi {

// The description checked against the device's image size limit.
stereo::StereoFrameDesc checkedDesc(const s3d_stereo_frame_desc& desc, std::uint32_t maxImageDimension2D);
// The dispatch checked against the frame (fields named as the C struct's), converted on the stack.
stereo::StereoFrameDispatch checkedDispatch(const stereo::StereoFrame& frame, const s3d_stereo_frame_dispatch& dispatch);
// The C API names the step (`function`) it refuses for another method than the hybrid.
void requireHybrid(const stereo::StereoFrame& frame, const char* function);
void toC(const stereo::HybridEyeCameras& eyes, s3d_eye_cameras* cameras);

}  // namespace s3d::capi
