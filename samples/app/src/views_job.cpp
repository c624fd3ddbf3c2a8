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
namespace {

glm::mat4 frustum(double l, double r, double u, double d, float nearPlane, float farPlane) {
  return glm::mat4(comfort::frustumProjection(l, r, u, d, nearPlane, farPlane));
}

// The center view's matrices: its own asymmetric frustum, and no weapon depth push (the eyes are parallel; the
// reference renders the true depths).
renderer::ViewMatrices centerViewFor(const renderer::Scene& scene, const comfort::CenterView& center) {
  renderer::ViewMatrices view = renderer::centerViewMatrices(scene, float(center.width) / float(center.height), {0.0f, 1.0f});
  view.worldProjection = frustum(center.tanLeft, center.tanRight, center.tanUp, center.tanDown,
                                 scene.camera.nearPlane, scene.camera.farPlane);
  view.firstPersonProjection = frustum(center.tanLeft, center.tanRight, center.tanUp, center.tanDown,
                                       scene.firstPerson.nearPlane, scene.firstPerson.farPlane);
  return view;
}

// Eye `index`'s own camera: the center's, offset along x, with the eye's asymmetric frustum.
renderer::ViewMatrices eyeViewFor(const renderer::Scene& scene, const renderer::ViewMatrices& centerView,
                                  const comfort::CenterView& center, const comfort::EyeView& eye, int index) {
  glm::mat4 toEye(1.0f);
  toEye[3][0] = float(-center.eyeOffset[std::size_t(index)]);  // the eye sits at +offset: points move by -offset
  renderer::ViewMatrices view = centerView;
  view.worldView = toEye * centerView.worldView;
  view.firstPersonView = toEye * centerView.firstPersonView;
  const double l = std::tan(eye.angleLeft), r = std::tan(eye.angleRight);
  const double u = std::tan(eye.angleUp), d = std::tan(eye.angleDown);
  view.worldProjection = frustum(l, r, u, d, scene.camera.nearPlane, scene.camera.farPlane);
  view.firstPersonProjection = frustum(l, r, u, d, scene.firstPerson.nearPlane, scene.firstPerson.farPlane);
  return view;
}

// The synthesized eye's range of disparity, in its pixels and in arcminutes: from its nearest and farthest depth.
void recordDisparityRange(ViewsReport& report, const DepthImage& eyeDepth, const comfort::EyeView& eye,
                          double worldScale, std::size_t index) {
  double nearest = INFINITY, farthest = 0.0;
  for (float d : eyeDepth.pixels)
    if (d > 0.0f) nearest = std::min(nearest, double(d)), farthest = std::max(farthest, double(d));
  if (!(farthest > 0.0)) return;
  const double separation = report.interocularMeters * worldScale;      // world units
  const double range = separation * (1.0 / nearest - 1.0 / farthest);  // tangent units
  const double pitch = (std::tan(eye.angleRight) - std::tan(eye.angleLeft)) / double(eye.width);
  report.disparityRangePx[index] = range / pitch;
  report.disparityRangeArcmin[index] = range * 180.0 * 60.0 / 3.14159265358979323846;
}

// A fresh renderer's render of `view`: its first frame, as in s3d render, is rendered twice.
ImageRGBA8 renderReference(vk::Context& context, const renderer::Scene& scene, const renderer::ViewMatrices& view,
                           std::uint32_t width, std::uint32_t height) {
  renderer::DeferredRenderer eyeRenderer(context, width, height);
  eyeRenderer.setScene(scene);
  (void)eyeRenderer.render(view);
  (void)eyeRenderer.render(view);
  return eyeRenderer.readDisplayColor();
}

void writeViewsOutputs(const ViewsJobOptions& options, ViewsReport& report, const ImageRGBA8& centerColor,
                       const std::array<ImageRGBA8, 2>& eyes, const std::array<ImageRGBA8, 2>& references) {
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

}  // namespace

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
  const renderer::ViewMatrices centerView = centerViewFor(scene, center);
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
  for (std::size_t i = 0; i < 2; ++i) {
    const comfort::EyeView& eye = options.views.eyes[i];
    DepthImage eyeDepth;
    eyes[i] = stereo::synthesizeEyeForView(centerColor, centerDepth, options.views, center, int(i), &eyeDepth);
    report.comfort[i] = comfort::eyeViewComfort(eyeDepth, options.views.worldScale, report.interocularMeters, options.display);
    recordDisparityRange(report, eyeDepth, eye, options.views.worldScale, i);
    references[i] = renderReference(context, scene, eyeViewFor(scene, centerView, center, eye, int(i)), eye.width, eye.height);
    report.error[i] = stereo::compareDisplayImages(eyes[i], references[i], 0);
  }
  if (options.writeImages) writeViewsOutputs(options, report, centerColor, eyes, references);
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
