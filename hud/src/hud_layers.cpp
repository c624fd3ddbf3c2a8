#include "s3d/hud/hud_layers.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace s3d::hud {
namespace {

// The smallest part of `canvas` holding every drawn pixel (at least 1 x 1), as a layer whose pivot is the canvas
// pixel (originX, originY).
HudLayer cropped(std::string name, const ImageRGBA8& canvas, int originX, int originY, float anchorX, float anchorY) {
  int x0 = int(canvas.width), y0 = int(canvas.height), x1 = 0, y1 = 0;
  for (std::uint32_t y = 0; y < canvas.height; ++y)
    for (std::uint32_t x = 0; x < canvas.width; ++x)
      if (canvas.at(x, y)[3] != 0) {
        x0 = std::min(x0, int(x));
        y0 = std::min(y0, int(y));
        x1 = std::max(x1, int(x) + 1);
        y1 = std::max(y1, int(y) + 1);
      }
  if (x1 <= x0) x0 = y0 = 0, x1 = y1 = 1;  // draws nothing: one transparent pixel
  HudLayer layer{std::move(name), ImageRGBA8(std::uint32_t(x1 - x0), std::uint32_t(y1 - y0)),
                 {anchorX, anchorY, originX - x0, originY - y0}};
  for (int y = y0; y < y1; ++y)
    std::copy_n(canvas.at(std::uint32_t(x0), std::uint32_t(y)), 4 * (x1 - x0),
                layer.pixels.at(0, std::uint32_t(y - y0)));
  return layer;
}

}  // namespace

LayerOrigin layerOrigin(const HudPlacement& placement, float offsetPx) {
  if (!std::isfinite(offsetPx)) throw std::invalid_argument("HUD layer: the eye offset must be finite");
  const float x = std::floor(std::clamp(placement.anchorX + offsetPx, -1.0e7f, 1.0e7f) + 0.5f);
  const float y = std::floor(std::clamp(placement.anchorY, -1.0e7f, 1.0e7f) + 0.5f);
  return {int(x) - placement.pivotX, int(y) - placement.pivotY};
}

float eyeOffsetPx(float parallaxPx, stereo::Eye eye) { return eye == stereo::Eye::Left ? -parallaxPx : parallaxPx; }

HudLayer panelHudLayer(const Panel& panel) {
  if (panel.width < 0 || panel.height < 0 || panel.textScale < 1)
    throw std::invalid_argument("HUD panel '" + panel.name + "': negative size or a text scale below 1");
  std::string text = panel.text;  // stb_easy_font takes a mutable char*
  const int scale = panel.textScale;
  // Room for the text wherever panelLayer puts it: right of the panel's left edge and up to half a glyph above.
  const int margin = 2 + 8 * scale;
  const int textWidth = 2 * scale + 2 + (stb_easy_font_width(text.data()) + 2) * scale;
  const int textHeight = (stb_easy_font_height(text.data()) + 2) * scale;
  const int width = margin + std::max(panel.width, textWidth) + margin;
  const int height = margin + std::max(panel.height, textHeight) + margin;
  Panel local = panel;
  local.x = margin;
  local.y = margin;
  const ImageRGBA8 canvas = panelLayer(std::uint32_t(width), std::uint32_t(height), local, 0.0f);
  return cropped(panel.name, canvas, margin, margin, float(panel.x), float(panel.y));
}

HudLayer crosshairHudLayer(std::uint32_t width, std::uint32_t height, const CrosshairStyle& style) {
  const int reach = style.gapPx + style.armLengthPx + style.thicknessPx + 2;  // arms, their thickness and outline
  ImageRGBA8 canvas(std::uint32_t(2 * reach + 1), std::uint32_t(2 * reach + 1));
  drawCrosshair(canvas, float(reach), float(reach), style);
  return cropped("crosshair", canvas, reach, reach, 0.5f * float(width - 1), 0.5f * float(height - 1));
}

std::vector<HudLayer> builtInHudLayers(std::uint32_t width, std::uint32_t height) {
  std::vector<HudLayer> layers;
  for (const Panel& panel : defaultPanels(width, height)) layers.push_back(panelHudLayer(panel));
  layers.push_back(crosshairHudLayer(width, height, crosshairStyleForHeight(height)));
  return layers;
}

ImageRGBA8 placedLayer(std::uint32_t width, std::uint32_t height, const ImageRGBA8& layer, int x, int y) {
  ImageRGBA8 placed(width, height);
  const long x0 = std::max(0L, long(x)), x1 = std::min(long(width), long(x) + long(layer.width));
  const long y0 = std::max(0L, long(y)), y1 = std::min(long(height), long(y) + long(layer.height));
  for (long py = y0; py < y1; ++py)
    for (long px = x0; px < x1; ++px)
      std::copy_n(layer.at(std::uint32_t(px - x), std::uint32_t(py - y)), 4, placed.at(std::uint32_t(px), std::uint32_t(py)));
  return placed;
}

BlendCounts compositeHud(ImageRGBA8& eye, stereo::Eye side, std::span<const HudLayer> layers,
                         std::span<const HudElementFrame> frames) {
  if (layers.size() != frames.size())
    throw std::invalid_argument("HUD: " + std::to_string(frames.size()) + " element states for " +
                                std::to_string(layers.size()) + " layers");
  BlendCounts total;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    if (frames[i].hidden) continue;
    const LayerOrigin origin = layerOrigin(layers[i].placement, eyeOffsetPx(frames[i].parallaxPx, side));
    const BlendCounts counts = compositeLayer(eye, layers[i].pixels, origin.x, origin.y, frames[i].fadesBehindWeapon);
    total.drawnPixels += counts.drawnPixels;
    total.fadedPixels += counts.fadedPixels;
  }
  return total;
}

}  // namespace s3d::hud
