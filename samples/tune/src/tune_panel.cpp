// `s3d tune`'s side panel (Dear ImGui): the stereo and comfort settings, the view, the frame's numbers and the
// comfort profile's file, one section per function.
#include "tune_panel.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "s3d/comfort/display_profile.h"
#include "s3d/renderer/scene.h"
#include "s3d/tune/tune_window.h"

namespace s3d::tune {
namespace {

std::string formatMs(const std::optional<double>& ms) {
  if (!ms) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f ms", *ms);
  return text;
}

// Combo over names; returns true when the choice changed.
bool comboOfNames(const char* label, std::string& value, const std::vector<std::string>& names) {
  bool changed = false;
  if (ImGui::BeginCombo(label, value.c_str())) {
    for (const std::string& name : names)
      if (ImGui::Selectable(name.c_str(), name == value)) {
        changed = name != value;
        value = name;
      }
    ImGui::EndCombo();
  }
  return changed;
}

void drawStereoSection(stereo::StereoParameters& s) {
  if (!ImGui::CollapsingHeader("Stereo", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::SliderFloat("max separation", &s.maxSeparation, 0.0f, 0.08f, "%.4f");
  ImGui::SliderFloat("zero-parallax dist", &s.zeroParallaxDistance, 0.1f, 20.0f, "%.2f m", ImGuiSliderFlags_Logarithmic);
  bool autoCrop = s.edgeCrop < 0.0f;
  if (ImGui::Checkbox("crop = separation", &autoCrop)) s.edgeCrop = autoCrop ? -1.0f : s.maxSeparation;
  if (!autoCrop) ImGui::SliderFloat("edge crop", &s.edgeCrop, 0.0f, 0.08f, "%.4f");
  std::string method = stereo::methodName(s.method);
  if (comboOfNames("method", method, stereo::stereoMethodNames()))
    s.method = stereo::parseStereoMethod(method);
  if (s.method == stereo::StereoMethod::Hybrid) {
    std::string base = stereo::methodName(s.hybridBase);
    if (comboOfNames("hybrid base", base, stereo::stereoMethodNames(false)))
      s.hybridBase = stereo::parseStereoMethod(base);
    ImGui::SliderFloat("hybrid budget", &s.hybridBudget, 0.0f, 1.0f, "%.3f");
    ImGui::SliderInt("hybrid cell (0: by width)", &s.hybridCell, 0, stereo::kHybridCellLimit);
    ImGui::SliderFloat("hybrid score floor", &s.hybridScoreFloor, 0.0f, 2.0f, "%.2f px");
  }
  if (s.method == stereo::StereoMethod::Search) ImGui::SliderInt("taps", &s.searchTaps, 1, S3D_STEREO_MAX_TAPS);
  if (s.method == stereo::StereoMethod::Iterative) ImGui::SliderInt("iterations", &s.iterations, 1, 16);
  std::string mapping = stereo::disparityMappingName(s.disparityMapping);
  if (comboOfNames("disparity mapping", mapping, {"linear", "nonlinear"}))
    s.disparityMapping = stereo::parseDisparityMapping(mapping);
}

void drawComfortSection(TuneSession& session, TuneSettings& edited) {
  comfort::ComfortProfile& profile = edited.profile;
  stereo::StereoParameters& s = profile.stereo;
  if (!ImGui::CollapsingHeader("Comfort", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::SliderFloat("weapon offset", &s.weaponDepthOffset, 0.0f, 5.0f, "%.2f m");
  ImGui::SliderFloat("weapon scale", &s.weaponDepthScale, 0.05f, 4.0f, "%.2f");
  ImGui::Checkbox("zero-parallax control", &edited.zeroParallaxControl);
  if (edited.zeroParallaxControl) {
    comfort::ZeroParallaxControlSettings& z = profile.zeroParallax;
    ImGui::SliderFloat("engage distance", &z.engageDistance, 0.1f, 10.0f, "%.2f m");
    ImGui::SliderFloat("release margin", &z.releaseMargin, 0.0f, 2.0f, "%.2f m");
    ImGui::SliderFloat("minimum distance", &z.minimumDistance, 0.05f, 5.0f, "%.2f m");
    ImGui::SliderFloat("response", &z.responseSeconds, 0.01f, 2.0f, "%.2f s");
    ImGui::SliderFloat("max change", &z.maxChangePerSecond, 0.05f, 10.0f, "%.2f m/s");
  }
  float crosshairDistance = profile.crosshair.distance.value_or(session.sceneCrosshairDistance());
  if (ImGui::SliderFloat("crosshair distance", &crosshairDistance, 0.25f, 50.0f, "%.2f m", ImGuiSliderFlags_Logarithmic))
    profile.crosshair.distance = crosshairDistance;
  ImGui::SliderFloat("crosshair margin", &profile.crosshair.margin, 0.0f, 2.0f, "%.2f m");
  std::string display = profile.display.name;  // a custom display from a profile shows its name
  if (comboOfNames("display", display, comfort::builtInDisplayProfileNames()))
    profile.display = comfort::builtInDisplayProfile(display);
  // Off: as `s3d render`, nothing in the frame gets negative parallax (weapon push, screen plane, HUD).
  ImGui::Checkbox("allow negative parallax", &profile.allowNegativeParallax);
}

void drawViewSection(TuneSession& session, TuneState& state) {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  std::string view = viewModeName(state.view);
  if (comboOfNames("view", view, viewModeNames())) state.view = parseViewMode(view);
  ImGui::Checkbox("reference every frame", &state.reference);
  int supersample = int(state.supersample);
  if (ImGui::SliderInt("supersample", &supersample, 1, 4)) state.supersample = std::uint32_t(supersample);
  std::string scene = state.scene;
  if (comboOfNames("scene", scene, renderer::builtInSceneNames())) {
    state.scene = scene;
    state.pathFrame = 0;
    session.loadScene(state);
  }
  int frame = int(state.pathFrame);
  if (session.pathLength() > 1 && ImGui::SliderInt("path frame", &frame, 0, int(session.pathLength()) - 1))
    session.setPathFrame(state, std::size_t(frame));
  ImGui::Checkbox("play camera path", &state.playPath);
  ImGui::TextDisabled("right mouse: look, W A S D: walk, Q E: down/up");
}

// The frame's GPU times and its error against the reference.
void drawTimingNumbers(const FrameNumbers& numbers, const std::string& deviceName, float frameSeconds) {
  ImGui::Text("%s, %.0f ms per frame", deviceName.c_str(), 1000.0 * frameSeconds);
  ImGui::Text("GPU center frame %s", formatMs(numbers.centerFrameGpuMs).c_str());
  for (const renderer::PassTiming& pass : numbers.centerPasses) ImGui::BulletText("%s %.2f ms", pass.name.c_str(), pass.gpuMs);
  ImGui::Text("GPU stereo pass %s", formatMs(numbers.stereoPassGpuMs).c_str());
  ImGui::Text("GPU reference eyes %s", formatMs(numbers.referenceEyesGpuMs).c_str());
  if (numbers.errorLeft && numbers.errorRight)
    ImGui::Text("vs reference: L %.2f dB, R %.2f dB, SSIM %.3f / %.3f", numbers.errorLeft->psnrDb,
                numbers.errorRight->psnrDb, numbers.errorLeft->ssim, numbers.errorRight->ssim);
}

// The frame's parallax, conflicts, zero-parallax plane, budget and mapping as applied.
void drawComfortNumbers(const FrameNumbers& numbers) {
  const comfort::ParallaxStatistics& p = numbers.comfort.parallax;
  ImGui::Text("parallax %.1f .. %.1f px (%.2f .. %.2f %%)", p.minParallaxPx, p.maxParallaxPx, p.minParallaxPercent,
              p.maxParallaxPercent);
  ImGui::Text("disparity %.1f .. %.1f arcmin", p.minDisparityArcmin, p.maxDisparityArcmin);
  ImGui::Text("beyond 1 deg %.1f %%, in front %.1f %%", 100.0 * numbers.shareBeyondComfort, 100.0 * p.shareNegative);
  ImGui::Text("window violations %llu px (widest %u columns)",
              (unsigned long long)numbers.comfort.windowViolationPixels, numbers.comfort.windowViolationColumns);
  ImGui::Text("conflicts: weapon %llu px, HUD %llu px", (unsigned long long)numbers.weaponConflictPixels,
              (unsigned long long)numbers.hudConflictPixels);
  const char* limited = numbers.zeroParallaxLimited ? " (held at nearest depth)" : "";
  if (numbers.nearestSurface)
    ImGui::Text("zero parallax %.2f m%s, nearest surface %.2f m", numbers.zeroParallaxDistance, limited,
                *numbers.nearestSurface);
  else
    ImGui::Text("zero parallax %.2f m%s", numbers.zeroParallaxDistance, limited);
  if (numbers.budget.rule != comfort::DisparityBudgetRule::Off) {
    const comfort::BudgetFrame& b = numbers.budget;
    ImGui::Text("budget 1 deg: %.1f px behind, %.1f px in front; used %.0f %%%s%s", b.budget.uncrossedPx(b.imageWidth),
                b.budget.crossedPx(b.imageWidth), 100.0 * b.choice.usedShare, b.choice.cut ? ", cut" : "",
                b.choice.forced ? ", forced" : "");
    ImGui::Text("budget choice: separation %.2f %% (target %.2f %%), zero parallax %.2f m (target %.2f m)",
                100.0 * b.choice.parameters.maxSeparation, 100.0 * b.choice.target.maxSeparation,
                b.choice.parameters.zeroParallaxDistance, b.choice.target.zeroParallaxDistance);
  }
  if (numbers.disparityMap.mapping == stereo::DisparityMapping::Nonlinear) {
    const gpu::DisparityMapConstants& m = numbers.disparityMap.map;
    std::string knots;
    for (int i = 0; i < m.knotCount; ++i) {
      char text[48];
      auto depth = [](float inverse) { return inverse > 0.0f ? 1.0f / inverse : INFINITY; };
      std::snprintf(text, sizeof(text), "%s%.2f>%.2f", i ? ", " : "", depth(m.inverseDepth[i]), depth(m.mapped[i]));
      knots += text;
    }
    ImGui::TextWrapped("nonlinear mapping (depth > as shown, m): %s; 5-95 %% of pixels span %.1f px",
                       knots.empty() ? "identity" : knots.c_str(),
                       numbers.comfort.parallax.p95ParallaxPx - numbers.comfort.parallax.p05ParallaxPx);
  }
  ImGui::Text("weapon push %.2f + %.2f d, crosshair %.2f m%s", numbers.weaponDepthOffset, numbers.weaponDepthScale,
              numbers.crosshairDepth, numbers.crosshairHitWorld ? " (hit)" : "");
  if (numbers.sanitizedDepthPixels > 0)
    ImGui::Text("%llu invalid depth pixels read as the screen plane", (unsigned long long)numbers.sanitizedDepthPixels);
  if (numbers.warning) ImGui::TextWrapped("warning: %s", numbers.warning->c_str());
}

void drawProfileSection(TuneState& state, PanelState& panel) {
  if (!ImGui::CollapsingHeader("Comfort profile", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::InputText("file", panel.profilePath, sizeof(panel.profilePath));
  if (ImGui::Button("Save")) {
    try {
      saveProfile(panel.profilePath, state.settings);
      panel.message = std::string("saved ") + panel.profilePath;
    } catch (const std::exception& error) {
      panel.message = error.what();
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Load")) {
    try {
      state.settings = loadProfile(panel.profilePath, state.settings);
      panel.message = std::string("loaded ") + panel.profilePath;
    } catch (const std::exception& error) {
      panel.message = error.what();
    }
  }
}

}  // namespace

void drawPanel(TuneSession& session, TuneState& state, const FrameNumbers& numbers, PanelState& panel,
               const std::string& deviceName, float frameSeconds) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - float(kPanelWidth), 0.0f));
  ImGui::SetNextWindowSize(ImVec2(float(kPanelWidth), io.DisplaySize.y));
  ImGui::Begin("s3d tune", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  ImGui::PushItemWidth(150.0f);
  // Edits go to a copy, taken only when the whole of it is valid.
  TuneSettings edited = state.settings;
  drawStereoSection(edited.profile.stereo);
  drawComfortSection(session, edited);
  try {
    validate(edited);
    state.settings = edited;
  } catch (const std::exception& error) {
    panel.message = std::string("not taken: ") + error.what();
  }
  drawViewSection(session, state);
  if (ImGui::CollapsingHeader("Numbers", ImGuiTreeNodeFlags_DefaultOpen)) {
    drawTimingNumbers(numbers, deviceName, frameSeconds);
    drawComfortNumbers(numbers);
  }
  drawProfileSection(state, panel);
  if (!panel.message.empty()) ImGui::TextWrapped("%s", panel.message.c_str());
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace s3d::tune
