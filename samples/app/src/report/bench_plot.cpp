// `s3d bench`'s speed-against-error plots (SVG): one labelled circle per row, one color per scene, the hybrid
// method's budgets joined into a curve per scene and separation.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "bench_text.h"
#include "s3d/app/bench_job.h"

namespace s3d::app {
namespace {

using namespace bench_text;

struct SpeedErrorAxes {
  const char* title;
  bool timeOverReferenceEye;  // x: both eyes' time / one reference eye's (else the stereo pass ms)
  bool wholeImage;            // y: whole-image PSNR (else the halo region's)
};

constexpr double kWidth = 900, kHeight = 560;
constexpr double kLeft = 70, kRight = 170, kTop = 40, kBottom = 60;
constexpr double kPlotWidth = kWidth - kLeft - kRight, kPlotHeight = kHeight - kTop - kBottom;
const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string number(double value) { return format("%.1f", value); }

struct Point {
  const BenchRow* row;
  double ms;      // the x value: ms, or a fraction of one reference eye
  double haloDb;  // the y value: mean of both eyes
};

// The rows that can be placed (a positive time for the log axis), and the scenes and separations among them in
// first-seen order (colours and sizes).
struct PlotPoints {
  std::vector<Point> points;
  std::vector<std::string> scenes;
  std::vector<float> separations;

  std::size_t sceneIndex(const std::string& scene) const {
    return std::size_t(std::find(scenes.begin(), scenes.end(), scene) - scenes.begin());
  }
  std::size_t separationIndex(float separation) const {
    return std::size_t(std::find(separations.begin(), separations.end(), separation) - separations.begin());
  }
};

PlotPoints plotPoints(const BenchReport& report, const SpeedErrorAxes& axes) {
  PlotPoints plot;
  for (const BenchRow& row : report.rows) {
    const std::optional<double> x = axes.timeOverReferenceEye ? ratio(row.stereoGpuMs, row.referenceEyeGpuMs)
                                                              : row.stereoGpuMs;
    if (!x || !(*x > 0.0)) continue;  // nothing to place on a log axis
    const stereo::ErrorStats stereo::EyeError::*region = axes.wholeImage ? &stereo::EyeError::display : &stereo::EyeError::halo;
    plot.points.push_back({&row, *x, 0.5 * ((row.left.*region).psnrDb + (row.right.*region).psnrDb)});
    if (std::find(plot.scenes.begin(), plot.scenes.end(), row.scene) == plot.scenes.end()) plot.scenes.push_back(row.scene);
    if (std::find(plot.separations.begin(), plot.separations.end(), row.maxSeparation) == plot.separations.end())
      plot.separations.push_back(row.maxSeparation);
  }
  return plot;
}

// Axes: x over whole ticks of 1, 2 and 5 per decade of ms, y over whole dB with a margin.
struct PlotScale {
  std::vector<double> ticks;
  double lowTick = 1.0, highTick = 10.0;  // the x axis's ends
  double minDb = 0.0, maxDb = 1.0, dbStep = 1.0;

  double xOf(double ms) const {
    const double firstLog = std::log10(lowTick), lastLog = std::log10(highTick);
    return kLeft + (std::log10(ms) - firstLog) / (lastLog - firstLog) * kPlotWidth;
  }
  double yOf(double db) const { return kTop + (maxDb - db) / (maxDb - minDb) * kPlotHeight; }
};

PlotScale plotScale(const std::vector<Point>& points) {
  double minMs = 1.0, maxMs = 10.0, minDb = 0.0, maxDb = 1.0;
  if (!points.empty()) {
    minMs = maxMs = points.front().ms;
    minDb = maxDb = points.front().haloDb;
    for (const Point& p : points) {
      minMs = std::min(minMs, p.ms), maxMs = std::max(maxMs, p.ms);
      minDb = std::min(minDb, p.haloDb), maxDb = std::max(maxDb, p.haloDb);
    }
  }
  // The x axis spans from the last tick at or below the fastest point to the first tick at or above the slowest.
  PlotScale scale;
  for (double decade = std::floor(std::log10(minMs)); decade <= std::ceil(std::log10(maxMs)); decade += 1.0)
    for (double mantissa : {1.0, 2.0, 5.0}) scale.ticks.push_back(mantissa * std::pow(10.0, decade));
  scale.lowTick = scale.ticks.front(), scale.highTick = scale.ticks.back();  // 10^ceil(log10(maxMs)) >= maxMs
  for (double tick : scale.ticks)
    if (tick <= minMs * (1 + 1e-9)) scale.lowTick = tick;
  for (auto tick = scale.ticks.rbegin(); tick != scale.ticks.rend(); ++tick)
    if (*tick >= maxMs * (1 - 1e-9)) scale.highTick = *tick;
  if (scale.highTick <= scale.lowTick) scale.highTick = scale.lowTick * 10.0;  // every point at one time
  minDb = std::floor(minDb) - 1.0;
  maxDb = std::ceil(maxDb) + 1.0;
  scale.dbStep = maxDb - minDb > 20 ? 5.0 : maxDb - minDb > 8 ? 2.0 : 1.0;
  scale.minDb = std::floor(minDb / scale.dbStep) * scale.dbStep;
  scale.maxDb = std::ceil(maxDb / scale.dbStep) * scale.dbStep;
  return scale;
}

// Title, grid, ticks, frame and axis labels.
void writeFrame(std::ostringstream& svg, const BenchReport& report, const SpeedErrorAxes& axes, const PlotScale& scale) {
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << kWidth << ' ' << kHeight << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  svg << "<rect x=\"0\" y=\"0\" width=\"" << kWidth << "\" height=\"" << kHeight << "\" fill=\"white\"/>\n";
  svg << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"14\">" << axes.title << ", "
      << xmlEscaped(report.deviceName) << ", " << report.width << "x" << report.height << "</text>\n";
  for (double ms : scale.ticks) {
    if (ms < scale.lowTick * (1 - 1e-9) || ms > scale.highTick * (1 + 1e-9)) continue;
    const bool decade = std::fabs(std::log10(ms) - std::round(std::log10(ms))) < 1e-9;
    const double x = scale.xOf(ms);
    svg << "<line x1=\"" << number(x) << "\" y1=\"" << kTop << "\" x2=\"" << number(x) << "\" y2=\""
        << kTop + kPlotHeight << "\" stroke=\"" << (decade ? "#bbbbbb" : "#eeeeee") << "\"/>\n";
    svg << "<text x=\"" << number(x) << "\" y=\"" << kTop + kPlotHeight + 16 << "\" text-anchor=\"middle\">"
        << format("%g", ms) << "</text>\n";
  }
  for (double db = scale.minDb; db <= scale.maxDb + 1e-9; db += scale.dbStep) {
    const double y = scale.yOf(db);
    svg << "<line x1=\"" << kLeft << "\" y1=\"" << number(y) << "\" x2=\"" << kLeft + kPlotWidth << "\" y2=\""
        << number(y) << "\" stroke=\"#dddddd\"/>\n";
    svg << "<text x=\"" << kLeft - 6 << "\" y=\"" << number(y + 4) << "\" text-anchor=\"end\">" << format("%g", db)
        << "</text>\n";
  }
  svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kPlotWidth << "\" height=\"" << kPlotHeight
      << "\" fill=\"none\" stroke=\"black\"/>\n";
  svg << "<text x=\"" << kLeft + kPlotWidth / 2 << "\" y=\"" << kHeight - 18
      << "\" text-anchor=\"middle\">"
      << (axes.timeOverReferenceEye ? "GPU time of both eyes / one reference eye (log scale; medians of "
                                    : "stereo pass GPU time, both eyes (ms, log scale; median of ")
      << report.repeat << ")</text>\n";
  svg << "<text transform=\"translate(18 " << kTop + kPlotHeight / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << (axes.wholeImage ? "whole-image" : "halo")
      << " PSNR, mean of both eyes (dB)</text>\n";
}

// The hybrid budgets of one scene and separation joined into a curve, in budget order.
void writeHybridCurves(std::ostringstream& svg, const PlotPoints& plot, const PlotScale& scale) {
  for (const std::string& scene : plot.scenes)
    for (float separation : plot.separations) {
      std::vector<const Point*> curve;
      for (const Point& p : plot.points)
        if (p.row->scene == scene && p.row->maxSeparation == separation &&
            p.row->setting.method == stereo::StereoMethod::Hybrid)
          curve.push_back(&p);
      if (curve.size() < 2) continue;
      std::sort(curve.begin(), curve.end(), [](const Point* a, const Point* b) { return a->row->setting.budget < b->row->setting.budget; });
      svg << "<polyline fill=\"none\" stroke-width=\"1.5\" stroke=\""
          << kPalette[plot.sceneIndex(scene) % std::size(kPalette)] << "\" points=\"";
      for (const Point* p : curve) svg << number(scale.xOf(p->ms)) << ',' << number(scale.yOf(p->haloDb)) << ' ';
      svg << "\"/>\n";
    }
}

// One circle per row: color = scene, radius grows with the separation; labelled with the setting.
void writePoints(std::ostringstream& svg, const PlotPoints& plot, const PlotScale& scale, const SpeedErrorAxes& axes) {
  for (const Point& p : plot.points) {
    const std::size_t scene = plot.sceneIndex(p.row->scene);
    const std::size_t separation = plot.separationIndex(p.row->maxSeparation);
    const double x = scale.xOf(p.ms), y = scale.yOf(p.haloDb);
    svg << "<circle cx=\"" << number(x) << "\" cy=\"" << number(y) << "\" r=\"" << 3 + 1.5 * double(separation)
        << "\" fill=\"" << kPalette[scene % std::size(kPalette)] << "\" fill-opacity=\"0.75\"><title>"
        << xmlEscaped(p.row->scene + " " + p.row->setting.name() + " sep " + percentText(p.row->maxSeparation) +
                      "%: " + (axes.timeOverReferenceEye ? format("%.3f", p.ms) + " of an eye, " : msText(p.ms) + " ms, ") +
                      format("%.2f", p.haloDb) + " dB")
        << "</title></circle>\n";
    svg << "<text x=\"" << number(x + 6) << "\" y=\"" << number(y - 4) << "\" font-size=\"9\">"
        << xmlEscaped(p.row->setting.name() +
                      (plot.separations.size() > 1 ? " " + percentText(p.row->maxSeparation) + "%" : ""))
        << "</text>\n";
  }
}

// Legend: scenes by color, separations by size (squares, so circles stay one per row).
void writeLegend(std::ostringstream& svg, const PlotPoints& plot) {
  double legendY = kTop + 10;
  const double legendX = kLeft + kPlotWidth + 16;
  for (std::size_t i = 0; i < plot.scenes.size(); ++i, legendY += 18)
    svg << "<rect x=\"" << legendX << "\" y=\"" << legendY - 9 << "\" width=\"10\" height=\"10\" fill=\""
        << kPalette[i % std::size(kPalette)] << "\"/><text x=\"" << legendX + 16 << "\" y=\"" << legendY << "\">"
        << xmlEscaped(plot.scenes[i]) << "</text>\n";
  legendY += 8;
  for (std::size_t i = 0; i < plot.separations.size(); ++i, legendY += 18) {
    const double size = 2 * (3 + 1.5 * double(i));
    svg << "<rect x=\"" << number(legendX + 5 - size / 2) << "\" y=\"" << number(legendY - 4 - size / 2)
        << "\" width=\"" << size << "\" height=\"" << size << "\" fill=\"#888888\"/><text x=\"" << legendX + 16
        << "\" y=\"" << legendY << "\">sep " << percentText(plot.separations[i]) << " %</text>\n";
  }
}

std::string speedErrorSvg(const BenchReport& report, const SpeedErrorAxes& axes) {
  const PlotPoints plot = plotPoints(report, axes);
  const PlotScale scale = plotScale(plot.points);
  std::ostringstream svg;
  writeFrame(svg, report, axes, scale);
  writeHybridCurves(svg, plot, scale);
  writePoints(svg, plot, scale, axes);
  writeLegend(svg, plot);
  if (plot.points.size() != report.rows.size())
    svg << "<text x=\"" << kLeft + 8 << "\" y=\"" << kTop + 16 << "\">" << report.rows.size() - plot.points.size()
        << " rows without GPU timestamps are not shown</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace

std::string benchSpeedErrorSvg(const BenchReport& report) {
  return speedErrorSvg(report, {"Stereo pass speed against halo error", false, false});
}

std::string benchTimeOverEyeSvg(const BenchReport& report) {
  return speedErrorSvg(report, {"Speed against whole-image error (hybrid budgets joined)", true, true});
}

}  // namespace s3d::app
