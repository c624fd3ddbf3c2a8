#pragma once
// Viewing geometry for the comfort report: on-screen parallax -> angular disparity for a given display.
#include <cstdint>
#include <string>
#include <vector>

#include "s3d/image.h"
#include "s3d/stereo/stereo.h"

namespace s3d::comfort {

struct DisplayProfile {
  std::string name;
  float screenWidthMeters = 1.218f;    // the image's width on the screen (55-inch 16:9 television)
  float viewingDistanceMeters = 2.5f;  // eyes to screen (for a head-mounted display: its focal distance)
  float interocularMeters = 0.063f;
};

// "tv55" (55-inch 16:9 at 2.5 m), "monitor27" (27-inch 16:9 at 0.7 m), "hmd" (90-degree horizontal field of
// view focused at 1.3 m, so the virtual screen is 2.6 m wide). Throws std::invalid_argument listing them.
DisplayProfile builtInDisplayProfile(const std::string& name);
std::vector<std::string> builtInDisplayProfileNames();

// Angular disparity in arcminutes of a point shown with on-screen parallax `parallaxMeters` (right-eye image
// minus left-eye image position; positive: behind the screen): the difference between the vergence angle of
// the screen and that of the point. Parallax at or beyond the interocular distance diverges the eyes: the
// result is then the screen's full vergence angle plus the excess, still finite.
double disparityArcminutes(const DisplayProfile& display, double parallaxMeters);

struct ParallaxStatistics {
  double minParallaxPx = 0.0, maxParallaxPx = 0.0;            // right-eye minus left-eye position
  double minParallaxPercent = 0.0, maxParallaxPercent = 0.0;  // of the image width
  double minDisparityArcmin = 0.0, maxDisparityArcmin = 0.0;
  double shareBeyondOneDegree = 0.0;  // pixels whose |disparity| exceeds 60 arcminutes (the 1-degree rule)
  double shareNegative = 0.0;         // pixels in front of the screen
};

// Over the pixels of the stereo pass's linear depth (weapon pushed): the parallax each pixel is given,
// 2 * parallaxFromDepth(depth) * width between the eyes.
ParallaxStatistics parallaxStatistics(const DepthImage& stereoDepth, const stereo::StereoParameters& parameters,
                                      const DisplayProfile& display);

}  // namespace s3d::comfort
