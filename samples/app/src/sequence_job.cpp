#include "s3d/app/sequence_job.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "s3d/app/render_job.h"
#include "s3d/comfort/crosshair.h"
#include "s3d/comfort/world_queries.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/stereo/metrics.h"
#include "s3d/stereo/output_formats.h"
#include "s3d/stereo/synthesis.h"

namespace s3d::app {
namespace {

// The pushed weapon's farthest point stays within this share of the distance to the nearest surface.
constexpr float kWeaponClearance = 0.9f;

// Weapon pixels whose pushed depth lies behind the world surface along the same pixel ray: the pushed
// weapon would appear behind a wall it is in front of.
void countWeaponConflicts(const comfort::WorldQueries& world, const renderer::Camera& camera,
                          const renderer::ViewMatrices& center, const DepthImage& pushed,
                          const std::vector<std::uint8_t>& weaponMask, SequenceFrame& frame) {
  const glm::mat4 worldFromView = glm::inverse(center.worldView);
  const glm::mat4& projection = center.worldProjection;
  for (std::uint32_t y = 0; y < pushed.height; ++y)
    for (std::uint32_t x = 0; x < pushed.width; ++x) {
      if (!weaponMask[std::size_t(y) * pushed.width + x]) continue;
      const float depth = *pushed.at(x, y);
      ++frame.weaponPixels;
      // The world camera's ray through this pixel, at unit view depth.
      const float ndcX = (float(x) + 0.5f) / float(pushed.width) * 2.0f - 1.0f;
      const float ndcY = (float(y) + 0.5f) / float(pushed.height) * 2.0f - 1.0f;
      const glm::vec3 viewDirection((ndcX + projection[2][0]) / projection[0][0],
                                    (ndcY + projection[2][1]) / projection[1][1], -1.0f);
      const glm::vec3 direction = glm::mat3(worldFromView) * viewDirection;
      const float lengthPerDepth = glm::length(viewDirection);
      if (std::optional<float> hit = world.castRay(camera.position, direction, depth * lengthPerDepth))
        if (*hit / lengthPerDepth < depth) ++frame.weaponConflictPixels;
    }
}

}  // namespace

SequenceReport runSequenceJob(vk::Context& context, const SequenceJobOptions& options) {
  if (options.width == 0 || options.height == 0 || options.width > kMaxImageSize || options.height > kMaxImageSize)
    throw std::invalid_argument("sequence: resolution outside 1.." + std::to_string(kMaxImageSize));
  if (!(options.framesPerSecond > 0.0f) || options.framesPerSecond > 1000.0f)
    throw std::invalid_argument("sequence: frames per second must be in (0, 1000]");
  stereo::validate(options.stereo);
  renderer::Scene scene = renderer::makeBuiltInScene(options.scene);
  if (scene.cameraPath.empty()) throw std::invalid_argument("scene '" + options.scene + "' has no camera path");
  comfort::ZeroParallaxControlSettings settings = options.zeroParallax;
  settings.restDistance = options.stereo.zeroParallaxDistance;
  settings.minimumDistance = std::min(settings.minimumDistance, settings.restDistance);
  comfort::ZeroParallaxController control(settings);  // validates the settings

  const comfort::WorldQueries world(scene);
  renderer::DeferredRenderer deferred(context, options.width, options.height, {options.supersample});
  deferred.setScene(scene);
  const float aspect = float(options.width) / float(options.height);
  const glm::vec2 weaponDepths = renderer::firstPersonDepthRange(scene).value_or(glm::vec2(0.0f));
  const std::uint32_t crop = std::uint32_t(stereo::makeStereoConstants(options.stereo, options.width, options.height).cropBegin);

  SequenceReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  for (std::size_t index = 0; index < scene.cameraPath.size(); ++index) {
    SequenceFrame frame;
    frame.index = index;
    scene.camera = renderer::cameraForFrame(scene, index);
    frame.nearestSurface = comfort::nearestSurfaceAhead(world, scene.camera, settings,
                                                        settings.engageDistance + settings.releaseMargin + 1.0f);
    frame.zeroParallaxDistance = control.update(frame.nearestSurface, 1.0f / options.framesPerSecond);
    // The weapon push shrinks with the zero-parallax distance (pushed = ratio * (offset + scale * depth)),
    // and at once, not smoothed, whenever its farthest pushed point would otherwise reach the nearest
    // surface: the pushed weapon must never appear behind a wall it is in front of.
    float ratio = frame.zeroParallaxDistance / settings.restDistance;
    if (frame.nearestSurface) {
      const float farthestPushed = options.stereo.weaponDepthOffset + options.stereo.weaponDepthScale * weaponDepths.y;
      ratio = std::min(ratio, kWeaponClearance * *frame.nearestSurface / farthestPushed);
    }
    stereo::StereoParameters parameters = options.stereo;
    parameters.zeroParallaxDistance = frame.zeroParallaxDistance;
    parameters.weaponDepthOffset = options.stereo.weaponDepthOffset * ratio;
    parameters.weaponDepthScale = options.stereo.weaponDepthScale * ratio;
    frame.weaponDepthOffset = parameters.weaponDepthOffset;
    frame.weaponDepthScale = parameters.weaponDepthScale;
    frame.crosshairDepth = comfort::placeCrosshair(world, scene.camera, scene.crosshairDistance).depth;

    const renderer::ViewMatrices center =
        renderer::centerViewMatrices(scene, aspect, {parameters.weaponDepthOffset, parameters.weaponDepthScale});
    deferred.render(center);
    const DepthImage pushed = deferred.readLinearDepth();
    countWeaponConflicts(world, scene.camera, center, pushed, deferred.readFirstPersonMask(), frame);
    stereo::SynthesisResult eyes = stereo::synthesizeTimed(context, deferred.displayColor(), deferred.linearDepth(), parameters);

    deferred.render(referenceEyeView(scene, center, stereo::Eye::Left, parameters));
    frame.psnrLeftDb = stereo::compareDisplayImages(eyes.eyes.left, deferred.readDisplayColor(), crop).psnrDb;
    deferred.render(referenceEyeView(scene, center, stereo::Eye::Right, parameters));
    frame.psnrRightDb = stereo::compareDisplayImages(eyes.eyes.right, deferred.readDisplayColor(), crop).psnrDb;

    if (options.writeFrames) {
      char name[48];
      std::snprintf(name, sizeof(name), "anaglyph_%04zu.png", index);
      io::writePng(options.outputFolder / name, stereo::makeAnaglyphDubois(eyes.eyes.left, eyes.eyes.right));
      report.filesWritten.push_back(name);
    }
    report.frames.push_back(frame);
  }
  report.filesWritten.push_back("report.json");
  io::writeTextFile(options.outputFolder / "report.json", toJson(report).dump(2) + "\n");
  return report;
}

nlohmann::json toJson(const SequenceReport& report) {
  nlohmann::json frames = nlohmann::json::array();
  for (const SequenceFrame& frame : report.frames)
    frames.push_back({{"frame", frame.index},
                      {"zeroParallaxDistance", frame.zeroParallaxDistance},
                      {"nearestSurface", frame.nearestSurface ? nlohmann::json(*frame.nearestSurface) : nullptr},
                      {"crosshairDepth", frame.crosshairDepth},
                      {"weaponDepthOffset", frame.weaponDepthOffset},
                      {"weaponDepthScale", frame.weaponDepthScale},
                      {"weaponPixels", frame.weaponPixels},
                      {"weaponConflictPixels", frame.weaponConflictPixels},
                      {"psnrDb", {{"left", frame.psnrLeftDb}, {"right", frame.psnrRightDb}}}});
  return {{"device", report.deviceName}, {"scene", report.scene}, {"frames", frames}, {"files", report.filesWritten}};
}

}  // namespace s3d::app
