#include "s3d/app/views_job.h"

#include <algorithm>
#include <cmath>

#include "s3d/app/comfort_json.h"
#include "s3d/app/report_json.h"
#include "s3d/frame/memory_budget.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene_animation.h"
#include "s3d/renderer/scene_file.h"
#include "s3d/stereo/eye_views_reference.h"

namespace s3d::app {
ViewsReport runViewsJob(vk::Context& context, const ViewsJobOptions& options) {
  if (!(options.framesPerSecond > 0.0f) || options.framesPerSecond > 1000.0f)
    throw std::invalid_argument("views: frames per second must be in (0, 1000]");
  renderer::Scene scene = renderer::loadScene(options.scene);
  scene.camera = renderer::cameraForFrame(scene, options.frame);
  renderer::poseScene(scene, double(options.frame) / double(options.framesPerSecond));  // before objects are dropped
  // The world layer only: the first-person layer's lighting in the eyes' own frusta does not match its center
  // render yet (a known limit, docs/DESIGN.md "View configurations").
  std::erase_if(scene.objects, [](const renderer::Object& o) { return o.layer == renderer::Layer::FirstPerson; });
  ViewsReport report;
  report.deviceName = context.deviceName();
  report.scene = options.scene;
  // Guard band down to the near plane: with parallel eyes every depth has parallax b / d.
  const comfort::CenterView& center = report.center = comfort::centerViewFor(options.views, scene.camera.nearPlane);
  auto frustum = [](double l, double r, double u, double d, float nearPlane, float farPlane) {
    return glm::mat4(comfort::frustumProjection(l, r, u, d, nearPlane, farPlane));
  };

  // The center view: no weapon depth push (the eyes are parallel; the reference renders the true depths).
  renderer::ViewMatrices centerView = renderer::centerViewMatrices(scene, float(center.width) / float(center.height), {0.0f, 1.0f});
  centerView.worldProjection = frustum(center.tanLeft, center.tanRight, center.tanUp, center.tanDown,
                                       scene.camera.nearPlane, scene.camera.farPlane);
  centerView.firstPersonProjection = frustum(center.tanLeft, center.tanRight, center.tanUp, center.tanDown,
                                             scene.firstPerson.nearPlane, scene.firstPerson.farPlane);
  // The center view dominates (the eyes' references are rendered one at a time after it).
  frame::requireMemory(context, frame::renderMemoryEstimate(center.width, center.height, center.width, 1), options.memoryLimitBytes);
  ImageRGBA8 centerColor;
  DepthImage centerDepth;  // NaN, 0, negative: read as infinity
  {
    renderer::DeferredRenderer deferred(context, center.width, center.height);  // one renderer alive at a time
    deferred.setScene(scene);
    (void)deferred.render(centerView);
    centerColor = deferred.readDisplayColor();
    centerDepth = deferred.readLinearDepth();
  }

  std::array<ImageRGBA8, 2> eyes, references;
  report.display = options.display;
  report.interocularMeters = options.views.eyes[1].positionX - options.views.eyes[0].positionX;
  for (int i = 0; i < 2; ++i) {
    const comfort::EyeView& eye = options.views.eyes[std::size_t(i)];
    DepthImage eyeDepth;
    eyes[std::size_t(i)] = stereo::synthesizeEyeForView(centerColor, centerDepth, options.views, center, i, &eyeDepth);
    report.comfort[std::size_t(i)] =
        comfort::eyeViewComfort(eyeDepth, options.views.worldScale, report.interocularMeters, options.display);
    double nearest = INFINITY, farthest = 0.0;
    for (float d : eyeDepth.pixels)
      if (d > 0.0f) nearest = std::min(nearest, double(d)), farthest = std::max(farthest, double(d));
    if (farthest > 0.0) {
      const double separation = report.interocularMeters * options.views.worldScale;  // world units
      const double range = separation * (1.0 / nearest - 1.0 / farthest);          // tangent units
      const double pitch = (std::tan(eye.angleRight) - std::tan(eye.angleLeft)) / double(eye.width);
      report.disparityRangePx[std::size_t(i)] = range / pitch;
      report.disparityRangeArcmin[std::size_t(i)] = range * 180.0 * 60.0 / 3.14159265358979323846;
    }
    // The reference: the eye's own camera, offset along x, with its own asymmetric frustum and size.
    renderer::DeferredRenderer eyeRenderer(context, eye.width, eye.height);
    eyeRenderer.setScene(scene);
    glm::mat4 toEye(1.0f);
    toEye[3][0] = float(-center.eyeOffset[std::size_t(i)]);  // the eye sits at +offset: points move by -offset
    renderer::ViewMatrices eyeView = centerView;
    eyeView.worldView = toEye * centerView.worldView;
    eyeView.firstPersonView = toEye * centerView.firstPersonView;
    const double l = std::tan(eye.angleLeft), r = std::tan(eye.angleRight);
    const double u = std::tan(eye.angleUp), d = std::tan(eye.angleDown);
    eyeView.worldProjection = frustum(l, r, u, d, scene.camera.nearPlane, scene.camera.farPlane);
    eyeView.firstPersonProjection = frustum(l, r, u, d, scene.firstPerson.nearPlane, scene.firstPerson.farPlane);
    (void)eyeRenderer.render(eyeView);  // the first frame of a fresh renderer, as in s3d render: rendered twice
    (void)eyeRenderer.render(eyeView);
    references[std::size_t(i)] = eyeRenderer.readDisplayColor();
    report.error[std::size_t(i)] = stereo::compareDisplayImages(eyes[std::size_t(i)], references[std::size_t(i)], 0);
  }

  if (options.writeImages) {
    const std::array<std::pair<const char*, const ImageRGBA8*>, 5> images{
        {{"center.png", &centerColor}, {"left.png", &eyes[0]}, {"right.png", &eyes[1]},
         {"left_reference.png", &references[0]}, {"right_reference.png", &references[1]}}};
    for (const auto& [name, image] : images) {
      io::writePng(options.outputFolder / name, *image);
      report.filesWritten.push_back(name);
    }
    report.filesWritten.push_back("report.json");
    nlohmann::json document = toJson(report);
    document["views"] = options.viewsFile;
    io::writeTextFile(options.outputFolder / "report.json", document.dump(2) + "\n");
  }
  return report;
}

nlohmann::json toJson(const ViewsReport& report) {
  auto stats = [](const stereo::ErrorStats& e) {
    return nlohmann::json{{"psnrDb", finiteOrNull(e.psnrDb)}, {"ssim", finiteOrNull(e.ssim)},
                          {"meanAbsoluteError", finiteOrNull(e.meanAbsoluteError)}, {"pixelCount", e.pixelCount}};
  };
  auto eyeComfort = [](const comfort::EyeViewComfort& e) {
    return nlohmann::json{{"pixelCount", e.pixelCount},
                          {"meanConflictDiopters", finiteOrNull(e.meanConflictDiopters)},
                          {"p95ConflictDiopters", finiteOrNull(e.p95ConflictDiopters)},
                          {"maxConflictDiopters", finiteOrNull(e.maxConflictDiopters)},
                          {"shareBeyondOneDegree", finiteOrNull(e.shareBeyondOneDegree)},
                          {"nearestMeters", finiteOrNull(e.nearestMeters)}};
  };
  const comfort::CenterView& c = report.center;
  return {{"device", report.deviceName},
          {"scene", report.scene},
          {"center", {{"width", c.width}, {"height", c.height}, {"tanLeft", c.tanLeft}, {"tanRight", c.tanRight},
                      {"tanUp", c.tanUp}, {"tanDown", c.tanDown}, {"eyeOffset", c.eyeOffset}}},
          {"error", {{"left", stats(report.error[0])}, {"right", stats(report.error[1])}}},
          {"disparityRangePx", {{"left", finiteOrNull(report.disparityRangePx[0])},
                                {"right", finiteOrNull(report.disparityRangePx[1])}}},
          {"disparityRangeArcmin", {{"left", finiteOrNull(report.disparityRangeArcmin[0])},
                                    {"right", finiteOrNull(report.disparityRangeArcmin[1])}}},
          {"comfort", {{"display", displayJson(report.display)},
                       {"focalDistanceMeters", report.display.viewingDistanceMeters},
                       {"interocularMeters", report.interocularMeters},
                       {"left", eyeComfort(report.comfort[0])},
                       {"right", eyeComfort(report.comfort[1])}}},
          {"files", report.filesWritten}};
}

}  // namespace s3d::app
