#include "s3d/comfort/comfort_profile.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "json_fields.h"

namespace s3d::comfort {
namespace {

using detail::ObjectReader;
using detail::Range;

constexpr Range kFraction{0.0, double(stereo::kMaxSeparationLimit)};  // of the screen width
constexpr Range kPositiveDistance{0.0, 1.0e4, true};                  // world units
constexpr Range kDistance{0.0, 1.0e4};
constexpr Range kPositiveSeconds{0.0, 60.0, true};
constexpr Range kSeconds{0.0, 60.0};

const std::vector<std::string> kMethods = {"seed", "search", "iterative", "forward", "hybrid"};
const std::vector<std::string> kHybridBases = {"seed", "search", "iterative", "forward"};

void readStereo(const nlohmann::json& section, stereo::StereoParameters& p) {
  ObjectReader reader(section, "stereo");
  reader.number("maxSeparation", p.maxSeparation, kFraction);
  reader.number("zeroParallaxDistance", p.zeroParallaxDistance, {0.0, 1.0e6, true});
  if (const nlohmann::json* crop = reader.find("edgeCrop"); crop && !crop->is_null())
    reader.number("edgeCrop", p.edgeCrop, kFraction);
  else if (crop)
    p.edgeCrop = -1.0f;  // null: the crop follows maxSeparation
  std::string method = stereo::methodName(p.method);
  reader.choice("method", method, kMethods);
  p.method = stereo::parseStereoMethod(method);
  reader.integer("searchTaps", p.searchTaps, 1, S3D_STEREO_MAX_TAPS);
  reader.integer("iterations", p.iterations, 1, 16);
  reader.number("hybridBudget", p.hybridBudget, {0.0, 1.0, false});
  reader.integer("hybridCell", p.hybridCell, 0, stereo::kHybridCellLimit);
  reader.number("hybridScoreFloor", p.hybridScoreFloor, {0.0, double(stereo::kHybridScoreFloorLimit), false});
  std::string base = stereo::methodName(p.hybridBase);
  reader.choice("hybridBase", base, kHybridBases);
  p.hybridBase = stereo::parseStereoMethod(base);
  std::string mapping = stereo::disparityMappingName(p.disparityMapping);
  reader.choice("disparityMapping", mapping, {"linear", "nonlinear"});
  p.disparityMapping = stereo::parseDisparityMapping(mapping);
  reader.finish();
}

void readWeapon(const nlohmann::json& section, stereo::StereoParameters& p) {
  ObjectReader reader(section, "weapon");
  reader.number("depthOffset", p.weaponDepthOffset, kDistance);
  reader.number("depthScale", p.weaponDepthScale, kPositiveDistance);
  reader.finish();
}

void readZeroParallaxControl(const nlohmann::json& section, ZeroParallaxControlSettings& s) {
  ObjectReader reader(section, "zeroParallaxControl");
  reader.number("engageDistance", s.engageDistance, kPositiveDistance);
  reader.number("releaseMargin", s.releaseMargin, kDistance);
  reader.number("minimumDistance", s.minimumDistance, kPositiveDistance);
  reader.number("responseSeconds", s.responseSeconds, kPositiveSeconds);
  reader.number("maxChangePerSecond", s.maxChangePerSecond, kPositiveDistance);
  reader.integer("ringRays", s.ringRays, 0, 64);
  reader.number("ringAngleRadians", s.ringAngleRadians, {0.0, 1.5, false, true});
  reader.finish();
}

void readCrosshair(const nlohmann::json& section, CrosshairSettings& c) {
  ObjectReader reader(section, "crosshair");
  if (const nlohmann::json* distance = reader.find("distance"); distance && !distance->is_null()) {
    float value = 0.0f;
    reader.number("distance", value, kPositiveDistance);
    c.distance = value;
  } else if (distance) {
    c.distance.reset();  // null: the scene's own crosshair distance
  }
  reader.number("margin", c.margin, {0.0, 100.0});
  reader.number("responseSeconds", c.responseSeconds, kSeconds);
  reader.finish();
}

}  // namespace

ZeroParallaxControlSettings ComfortProfile::zeroParallaxSettings() const {
  ZeroParallaxControlSettings settings = zeroParallax;
  settings.restDistance = stereo.zeroParallaxDistance;
  settings.minimumDistance = std::min(settings.minimumDistance, settings.restDistance);
  return settings;
}

ComfortProfile comfortProfileFromJson(const nlohmann::json& document) {
  ComfortProfile profile;
  ObjectReader reader(document, "");
  if (const nlohmann::json* section = reader.find("stereo")) readStereo(*section, profile.stereo);
  if (const nlohmann::json* section = reader.find("weapon")) readWeapon(*section, profile.stereo);
  if (const nlohmann::json* section = reader.find("zeroParallaxControl"))
    readZeroParallaxControl(*section, profile.zeroParallax);
  if (const nlohmann::json* section = reader.find("crosshair")) readCrosshair(*section, profile.crosshair);
  if (const nlohmann::json* display = reader.find("display")) {
    if (display->is_string()) {
      try {
        profile.display = builtInDisplayProfile(display->get<std::string>());
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument(std::string("'display': ") + error.what());
      }
    } else {
      profile.display = displayProfileFromJson(*display);
    }
  }
  reader.boolean("allowNegativeParallax", profile.allowNegativeParallax);
  reader.finish();
  // Consistency between keys (each key alone is in range by now).
  stereo::validate(profile.stereo);
  validate(profile.zeroParallaxSettings());
  validate(profile.display);
  return profile;
}

void validate(const ComfortProfile& profile) {
  // The JSON reader holds every range and consistency rule; a NaN becomes null and is refused as not a number.
  (void)comfortProfileFromJson(toJson(profile));
}

nlohmann::json toJson(const ComfortProfile& profile) {
  const stereo::StereoParameters& s = profile.stereo;
  const ZeroParallaxControlSettings& z = profile.zeroParallax;
  const CrosshairSettings& c = profile.crosshair;
  nlohmann::json display = toJson(profile.display);
  for (const std::string& name : builtInDisplayProfileNames())
    if (toJson(builtInDisplayProfile(name)) == display) display = name;  // a built-in one by its name
  return {{"stereo",
           {{"maxSeparation", detail::shortest(s.maxSeparation)},
            {"zeroParallaxDistance", detail::shortest(s.zeroParallaxDistance)},
            {"edgeCrop", s.edgeCrop < 0.0f ? nlohmann::json() : nlohmann::json(detail::shortest(s.edgeCrop))},
            {"method", stereo::methodName(s.method)},
            {"searchTaps", s.searchTaps},
            {"iterations", s.iterations},
            {"hybridBudget", detail::shortest(s.hybridBudget)},
            {"hybridCell", s.hybridCell},
            {"hybridScoreFloor", detail::shortest(s.hybridScoreFloor)},
            {"hybridBase", stereo::methodName(s.hybridBase)},
            {"disparityMapping", stereo::disparityMappingName(s.disparityMapping)}}},
          {"weapon", {{"depthOffset", detail::shortest(s.weaponDepthOffset)}, {"depthScale", detail::shortest(s.weaponDepthScale)}}},
          {"zeroParallaxControl",
           {{"engageDistance", detail::shortest(z.engageDistance)},
            {"releaseMargin", detail::shortest(z.releaseMargin)},
            {"minimumDistance", detail::shortest(z.minimumDistance)},
            {"responseSeconds", detail::shortest(z.responseSeconds)},
            {"maxChangePerSecond", detail::shortest(z.maxChangePerSecond)},
            {"ringRays", z.ringRays},
            {"ringAngleRadians", detail::shortest(z.ringAngleRadians)}}},
          {"crosshair",
           {{"distance", c.distance ? nlohmann::json(detail::shortest(*c.distance)) : nlohmann::json()},
            {"margin", detail::shortest(c.margin)},
            {"responseSeconds", detail::shortest(c.responseSeconds)}}},
          {"display", display},
          {"allowNegativeParallax", profile.allowNegativeParallax}};
}

ComfortProfile loadComfortProfile(const std::filesystem::path& file) {
  const nlohmann::json document = detail::readJsonFile(file, "comfort profile");
  try {
    return comfortProfileFromJson(document);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument("comfort profile '" + file.string() + "': " + error.what());
  }
}

void saveComfortProfile(const std::filesystem::path& file, const ComfortProfile& profile) {
  validate(profile);
  detail::writeTextAtomically(file, toJson(profile).dump(2) + "\n", "comfort profile");
}

}  // namespace s3d::comfort
