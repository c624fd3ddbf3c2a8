// Preamble for headers compiled both as C++ and as GLSL, so a parameter or a formula shared by the CPU and
// the GPU is written once and cannot drift (the FidelityFX / niagara pattern).
#ifndef S3D_GPU_SHARED_H
#define S3D_GPU_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#define S3D_GPU_BEGIN namespace s3d::gpu {
#define S3D_GPU_END }
#define S3D_INLINE inline
#define S3D_INFINITY (std::numeric_limits<float>::infinity())
namespace s3d::gpu {
using uint = std::uint32_t;
using glm::abs;
using glm::dot;
using glm::exp2;
using glm::floor;
using glm::mat4;
using glm::max;
using glm::min;
using glm::mix;
using glm::pow;
using glm::sqrt;
using glm::step;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
}  // namespace s3d::gpu
#else
#define S3D_GPU_BEGIN
#define S3D_GPU_END
#define S3D_INLINE
#define S3D_INFINITY (uintBitsToFloat(0x7f800000u))
#endif

#endif  // S3D_GPU_SHARED_H
