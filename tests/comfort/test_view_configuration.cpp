// View configurations: the center view covering both eyes, the eye-to-center mapping against projected eye
// cameras (1e-4 px, double precision), and view files with bad or missing fields.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "s3d/comfort/view_configuration.h"

namespace s3d::comfort {
namespace {

ViewConfiguration headsetLike() {
  ViewConfiguration views;
  views.eyes[0] = {-0.0315, -0.7854, 0.6981, 0.7330, -0.8203, 183, 192};
  views.eyes[1] = {0.0315, -0.6981, 0.7854, 0.7330, -0.8203, 183, 192};
  views.worldScale = 1.5;
  return views;
}

glm::dvec2 pixelOf(const glm::dmat4& projection, const glm::dmat4& view, const glm::dvec3& world, double width,
                   double height) {
  const glm::dvec4 clip = projection * view * glm::dvec4(world, 1.0);
  return {(clip.x / clip.w * 0.5 + 0.5) * width, (clip.y / clip.w * 0.5 + 0.5) * height};
}

TEST(ViewConfiguration, EyePixelsMapToTheCenterPixelThatSeesTheSamePoint) {
  // Each eye rendered by its own camera (offset along x, its own asymmetric frustum) sees a world point
  // at the eye pixel; the mapping from that pixel and the point's depth must land on the center camera's
  // pixel of the same point, to 1e-4 px.
  const ViewConfiguration views = headsetLike();
  const CenterView center = centerViewFor(views, 0.2);
  const glm::dmat4 centerView = glm::lookAt(glm::dvec3(1.0, 1.7, 6.0), glm::dvec3(0.3, 1.2, -4.0), glm::dvec3(0, 1, 0));
  const glm::dmat4 centerProjection =
      frustumProjection(center.tanLeft, center.tanRight, center.tanUp, center.tanDown, 0.1, 1000.0);
  const glm::dmat4 worldFromView = glm::inverse(centerView);
  for (int eye = 0; eye < 2; ++eye) {
    const EyeView& e = views.eyes[std::size_t(eye)];
    glm::dmat4 toEye(1.0);
    toEye[3][0] = -center.eyeOffset[std::size_t(eye)];  // the eye sits at +offset: points move by -offset
    const glm::dmat4 eyeView = toEye * centerView;
    const glm::dmat4 eyeProjection = frustumProjection(std::tan(e.angleLeft), std::tan(e.angleRight),
                                                       std::tan(e.angleUp), std::tan(e.angleDown), 0.1, 1000.0);
    for (double depth : {0.2, 0.7, 3.0, 40.0, 900.0})
      for (double tx : {-0.9, -0.2, 0.0, 0.5, 0.95})
        for (double ty : {-0.9, 0.1, 0.7}) {
          const glm::dvec3 world(worldFromView * glm::dvec4(tx * depth, ty * depth, -depth, 1.0));
          const glm::dvec2 eyePixel = pixelOf(eyeProjection, eyeView, world, e.width, e.height);
          const glm::dvec2 expected = pixelOf(centerProjection, centerView, world, center.width, center.height);
          const glm::dvec2 mapped = centerPixelForEyePixel(views, center, eye, eyePixel, depth);
          EXPECT_NEAR(mapped.x, expected.x, 1e-4) << "eye " << eye << " depth " << depth << " tx " << tx;
          EXPECT_NEAR(mapped.y, expected.y, 1e-4) << "eye " << eye << " depth " << depth << " ty " << ty;
        }
  }
}

TEST(ViewConfiguration, TheCenterViewCoversEveryEyePixelDownToTheNearestDepth) {
  const ViewConfiguration views = headsetLike();
  const double nearest = 0.2;
  const CenterView center = centerViewFor(views, nearest);
  EXPECT_NEAR(center.eyeOffset[0], -0.0315 * 1.5, 1e-15);  // world units: metres times the world scale
  for (int eye = 0; eye < 2; ++eye)
    for (double u : {0.0, double(views.eyes[std::size_t(eye)].width)})
      for (double v : {0.0, double(views.eyes[std::size_t(eye)].height)})
        for (double depth : {nearest, 1.0, 1e9}) {
          const glm::dvec2 c = centerPixelForEyePixel(views, center, eye, {u, v}, depth);
          EXPECT_GE(c.x, -1e-9);
          EXPECT_LE(c.x, center.width + 1e-9);
          EXPECT_GE(c.y, -1e-9);
          EXPECT_LE(c.y, center.height + 1e-9);
        }
  // No coarser than the finest eye: the center's pitch in tangent space is at most each eye's.
  for (const EyeView& e : views.eyes)
    EXPECT_LE((center.tanRight - center.tanLeft) / center.width,
              (std::tan(e.angleRight) - std::tan(e.angleLeft)) / e.width + 1e-15);
}

TEST(ViewConfiguration, TheExampleFilesLoad) {
  for (const char* name : {"tv-pair.json", "headset-pair.json"}) {
    const ViewConfiguration views = loadViewConfiguration(std::string(S3D_TEST_DATA_DIR) + "/../../samples/views/" + name);
    EXPECT_LT(views.eyes[0].positionX, views.eyes[1].positionX) << name;
  }
}

std::string errorFor(const std::string& text) {
  const std::string path = ::testing::TempDir() + "s3d_views_test.json";
  std::ofstream(path) << text;
  try {
    (void)loadViewConfiguration(path);
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find("views file '" + path + "': "), 0u) << message;
    return message.substr(message.find("': ") + 3);
  }
  ADD_FAILURE() << "accepted: " << text;
  return {};
}

TEST(ViewConfiguration, BadFilesAreRejectedWithOneErrorNamingTheFileAndField) {
  const std::string eye = R"("position": [0.03, 0, 0], "angleLeft": -0.7, "angleRight": 0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 64, "height": 64)";
  const std::string left = R"("left": {"position": [-0.03, 0, 0], "angleLeft": -0.7, "angleRight": 0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 64, "height": 64})";
  EXPECT_EQ(errorFor("{\"views\": {" + left + "}}"), "views.right is missing");
  EXPECT_EQ(errorFor("{\"views\": {" + left + ", \"right\": {" + eye + ", \"fov\": 1}}}"), "views.right.fov is not a known field");
  EXPECT_EQ(errorFor(R"({"views": {"left": {"position": [-0.03, 0, 0], "angleRight": 0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 64, "height": 64}, "right": {)" + eye + "}}}"),
            "views.left.angleLeft is missing");
  EXPECT_EQ(errorFor(R"({"views": {"left": {"position": [-0.03, 0, 0], "angleLeft": 0.7, "angleRight": -0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 64, "height": 64}, "right": {)" + eye + "}}}"),
            "views.left.angleRight must be greater than angleLeft");
  EXPECT_EQ(errorFor(R"({"views": {"left": {"position": [-0.03, 0, 0], "angleLeft": -2, "angleRight": 0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 64, "height": 64}, "right": {)" + eye + "}}}"),
            "views.left.angleLeft must be in (-pi/2, pi/2) radians");
  EXPECT_EQ(errorFor(R"({"views": {"left": {"position": [-0.03, 0.01, 0], "angleLeft": -0.7, "angleRight": 0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 64, "height": 64}, "right": {)" + eye + "}}}"),
            "views.left.position[1] must be 0 (eyes offset along x only)");
  EXPECT_EQ(errorFor(R"({"views": {"left": {"position": [-0.03, 0, 0], "angleLeft": -0.7, "angleRight": 0.7, "angleUp": 0.7, "angleDown": -0.7, "width": 0, "height": 64}, "right": {)" + eye + "}}}"),
            "views.left.width must be an integer in [1, 16384]");
  EXPECT_EQ(errorFor("{\"worldScale\": -1, \"views\": {" + left + ", \"right\": {" + eye + "}}}"), "worldScale must be positive");
  EXPECT_EQ(errorFor("{\"views\": {\"left\": {" + eye + "}, \"right\": {" + eye + "}}}"),
            "views.right.position[0] must be greater than the left eye's (the right eye is to the right)");
  EXPECT_EQ(errorFor("{\"views\": ").rfind("not valid JSON: parse error at line 1", 0), 0u);
  EXPECT_EQ(errorFor("[]"), "the document must be an object");
}

}  // namespace
}  // namespace s3d::comfort
