#include "s3d/hud/overlay.h"

#include "s3d/hud/layer_blend.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace s3d::hud {
namespace {

void fillRect(ImageRGBA8& image, int x0, int y0, int x1, int y1, const Color& color) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, int(image.width));
  y1 = std::min(y1, int(image.height));
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) std::copy(color.begin(), color.end(), image.at(std::uint32_t(x), std::uint32_t(y)));
}

// stb_easy_font's vertex: x, y, z floats and 4 color bytes; 4 vertices per axis-aligned quad.
struct FontVertex {
  float x, y, z;
  unsigned char color[4];
};
static_assert(sizeof(FontVertex) == 16, "stb_easy_font writes 16-byte vertices");

}  // namespace

std::vector<Panel> defaultPanels(std::uint32_t width, std::uint32_t height, float depth) {
  const float scale = float(height) / 720.0f;
  auto px = [&](float value) { return std::max(1, int(std::lround(value * scale))); };
  const int panelWidth = px(220.0f), panelHeight = px(56.0f), margin = px(32.0f);
  const int textScale = std::max(1, px(3.0f));
  Panel health;
  health.name = "health";
  health.x = margin;
  health.y = int(height) - margin - panelHeight;
  health.width = panelWidth;
  health.height = panelHeight;
  health.depth = depth;
  health.text = "HEALTH 100";
  health.textScale = textScale;
  Panel ammo = health;
  ammo.name = "ammo";
  ammo.x = int(width) - margin - panelWidth;
  ammo.text = "AMMO 30/90";
  return {health, ammo};
}

void drawText(ImageRGBA8& layer, int x, int y, const std::string& text, const Color& color, int scale) {
  if (scale < 1) throw std::invalid_argument("drawText: scale must be >= 1");
  std::vector<FontVertex> vertices(text.size() * 270 / 4 + 64);  // stb: about 270 bytes per character
  std::string buffer = text;  // stb_easy_font_print takes a mutable char*
  const int quads = stb_easy_font_print(0.0f, 0.0f, buffer.data(), nullptr, vertices.data(),
                                        int(vertices.size() * sizeof(FontVertex)));
  for (int q = 0; q < quads; ++q) {
    const FontVertex& a = vertices[std::size_t(q) * 4];
    const FontVertex& c = vertices[std::size_t(q) * 4 + 2];
    fillRect(layer, x + int(std::lround(a.x)) * scale, y + int(std::lround(a.y)) * scale,
             x + int(std::lround(c.x)) * scale, y + int(std::lround(c.y)) * scale, color);
  }
}

ImageRGBA8 panelLayer(std::uint32_t width, std::uint32_t height, const Panel& panel, float offsetPx) {
  ImageRGBA8 layer(width, height);  // transparent: alpha 0
  if (!std::isfinite(offsetPx)) throw std::invalid_argument("panelLayer: the offset must be finite");
  const int x = panel.x + int(std::floor(offsetPx + 0.5f));  // rounded half up, like the crosshair
  fillRect(layer, x, panel.y, x + panel.width, panel.y + panel.height, panel.border);
  fillRect(layer, x + 1, panel.y + 1, x + panel.width - 1, panel.y + panel.height - 1, panel.fill);
  const int glyphHeight = 7 * panel.textScale;
  drawText(layer, x + 2 * panel.textScale + 2, panel.y + (panel.height - glyphHeight) / 2, panel.text,
           panel.textColor, panel.textScale);
  return layer;
}

BlendCounts blendLayer(ImageRGBA8& eye, const ImageRGBA8& layer, bool behindWeapon) {
  if (eye.width != layer.width || eye.height != layer.height)
    throw std::invalid_argument("blendLayer: the layer and the eye differ in size");
  return compositeLayer(eye, layer, 0, 0, behindWeapon);  // the HUD pass's per-pixel math (hud_pass_shared.h)
}

std::uint64_t countDepthConflicts(const ImageRGBA8& centerLayer, float elementDepth, const DepthImage& stereoDepth,
                                  const std::vector<std::uint8_t>& weaponMask, bool behindWeapon) {
  if (centerLayer.width != stereoDepth.width || centerLayer.height != stereoDepth.height ||
      weaponMask.size() != stereoDepth.pixelCount())
    throw std::invalid_argument("countDepthConflicts: the layer, the depth and the mask differ in size");
  std::uint64_t conflicts = 0;
  for (std::size_t i = 0; i < stereoDepth.pixelCount(); ++i) {
    if (centerLayer.pixels[4 * i + 3] == 0) continue;
    if (behindWeapon && weaponMask[i]) continue;  // faded out there: not seen, no conflict
    if (elementDepth > stereoDepth.pixels[i]) ++conflicts;
  }
  return conflicts;
}

void makeOpaque(ImageRGBA8& image) {
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
}

}  // namespace s3d::hud
