#include "preview/comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "preview/bitmap_font.h"

namespace brdfit::preview {
namespace {

const std::array<float, 3> kLabelInk = {1.0f, 1.0f, 1.0f};
const std::array<float, 3> kLabelBand = {0.08f, 0.08f, 0.08f};
const std::array<float, 3> kNoData = {0.18f, 0.18f, 0.18f};

void Blit(const Image& src, Image* dst, int x0, int y0) {
  for (int y = 0; y < src.height && y0 + y < dst->height; ++y) {
    for (int x = 0; x < src.width && x0 + x < dst->width; ++x) {
      std::copy_n(src.At(x, y), 4, dst->At(x0 + x, y0 + y));
    }
  }
}

// Label on a dark band at the top of a panel. One size for every panel of an image (it depends
// on the panel width, not on the text: labels of different lengths look alike); a label too long
// for it drops to scale 1.
void Label(Image* img, int x0, int y0, int w, const std::string& text) {
  int scale = w >= 400 ? 2 : 1;
  if (TextWidth(text, scale) + 8 > w) scale = 1;
  FillRect(img, x0, y0, w, kGlyphHeight * scale + 6, kLabelBand);
  DrawText(img, x0 + 4, y0 + 3, text, scale, kLabelInk);
}

std::string Percent(double e) {
  char b[32];
  std::snprintf(b, sizeof b, e < 0.1 ? "%.2g%%" : "%.3g%%", 100 * e);
  return b;
}

}  // namespace

std::array<float, 3> ErrorColour(double e) {
  // Five stops, dark violet -> magenta -> orange -> pale yellow (chosen for this project).
  static const float stops[5][3] = {{0.05f, 0.03f, 0.20f}, {0.32f, 0.10f, 0.55f},
                                    {0.75f, 0.20f, 0.45f}, {0.98f, 0.55f, 0.20f},
                                    {0.99f, 0.95f, 0.60f}};
  const double t = std::clamp((std::log10(std::max(e, 1e-12)) + 3.0) / 3.0, 0.0, 1.0) * 4.0;
  const int i = std::min(static_cast<int>(t), 3);
  const float f = static_cast<float>(t - i);
  return {stops[i][0] + f * (stops[i + 1][0] - stops[i][0]),
          stops[i][1] + f * (stops[i + 1][1] - stops[i][1]),
          stops[i][2] + f * (stops[i + 1][2] - stops[i][2])};
}

std::vector<double> RelativeError(const Image& fitted, const Image& measured) {
  auto lum = [](const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; };
  double peak = 0;
  for (int y = 0; y < measured.height; ++y) {
    for (int x = 0; x < measured.width; ++x) peak = std::max(peak, lum(measured.At(x, y)));
  }
  std::vector<double> e(static_cast<std::size_t>(measured.width) * measured.height, -1.0);
  for (int y = 0; y < measured.height; ++y) {
    for (int x = 0; x < measured.width; ++x) {
      const float* m = measured.At(x, y);
      const double ym = lum(m);
      if (m[3] <= 0 || !(ym > 1e-4 * peak)) continue;
      e[static_cast<std::size_t>(y) * measured.width + x] = std::abs(lum(fitted.At(x, y)) - ym) / ym;
    }
  }
  return e;
}

Image RenderComparison(Renderer& renderer, const Scene& scene, const MaterialSet& materials,
                       int width, int height, ExplainLog* log, ComparisonStats* stats) {
  const ComparisonSpec& c = scene.comparison;
  struct Panel {
    std::string label, material;
    bool error = false;
  };
  std::vector<Panel> panels = {{"measured: " + c.measured, c.measured}};
  for (const auto& f : c.fitted) {
    const auto it = materials.find(f);
    panels.push_back({"fit: " + (it != materials.end() ? it->second.model : f), f});
  }
  if (!c.factored.empty()) panels.push_back({"factored", c.factored});
  if (!c.fitted.empty()) panels.push_back({"error", "", true});
  const int n = static_cast<int>(panels.size());
  const int cols = static_cast<int>(std::ceil(std::sqrt(n)));
  const int rows = (n + cols - 1) / cols;
  const int pw = width / cols, ph = height / rows;

  Image out(width, height);
  FillRect(&out, 0, 0, width, height, {0, 0, 0});
  Image measured_linear, fitted_linear;
  for (int k = 0; k < n; ++k) {
    const Panel& p = panels[static_cast<std::size_t>(k)];
    const int x0 = (k % cols) * pw, y0 = (k / cols) * ph;
    if (p.error) {
      const std::vector<double> e = RelativeError(fitted_linear, measured_linear);
      std::vector<double> lit;
      Image panel(pw, ph);
      for (int y = 0; y < ph; ++y) {
        for (int x = 0; x < pw; ++x) {
          const double v = e[static_cast<std::size_t>(y) * pw + x];
          const auto rgb = v < 0 ? (measured_linear.At(x, y)[3] > 0 ? kNoData
                                                                    : std::array<float, 3>{0, 0, 0})
                                 : ErrorColour(v);
          FillRect(&panel, x, y, 1, 1, rgb);
          if (v >= 0) lit.push_back(v);
        }
      }
      ComparisonStats s;
      if (!lit.empty()) {
        std::sort(lit.begin(), lit.end());
        s.median_error = lit[lit.size() / 2];
        s.p95_error = lit[std::min(lit.size() - 1, lit.size() * 95 / 100)];
        s.max_error = lit.back();
        s.pixels = static_cast<long>(lit.size());
      }
      if (stats) *stats = s;
      Blit(panel, &out, x0, y0);
      // Colour bar: 0.1 % .. 100 % along the bottom of the panel.
      const int bar_h = 8, bar_y = y0 + ph - bar_h - 14, bar_x = x0 + 8, bar_w = pw - 16;
      for (int x = 0; x < bar_w; ++x) {
        FillRect(&out, bar_x + x, bar_y, 1, bar_h,
                 ErrorColour(std::pow(10.0, -3.0 + 3.0 * x / std::max(1, bar_w - 1))));
      }
      DrawText(&out, bar_x, bar_y + bar_h + 3, "0.1%", 1, kLabelInk);
      DrawText(&out, bar_x + bar_w / 3 - TextWidth("1%", 1) / 2, bar_y + bar_h + 3, "1%", 1,
               kLabelInk);
      DrawText(&out, bar_x + 2 * bar_w / 3 - TextWidth("10%", 1) / 2, bar_y + bar_h + 3, "10%", 1,
               kLabelInk);
      DrawText(&out, bar_x + bar_w - TextWidth("100%", 1), bar_y + bar_h + 3, "100%", 1,
               kLabelInk);
      Label(&out, x0, y0, pw, "error med " + Percent(s.median_error) + " p95 " +
                                  Percent(s.p95_error));
      if (log) {
        log->Add("note", "comparison error of '" + c.fitted.front() + "' vs '" + c.measured +
                             "': median " + Percent(s.median_error) + ", 95th percentile " +
                             Percent(s.p95_error) + ", max " + Percent(s.max_error) + " over " +
                             std::to_string(s.pixels) + " pixels");
      }
      continue;
    }
    const auto it = materials.find(p.material);
    if (it == materials.end()) {
      FillRect(&out, x0, y0, pw, ph, kNoData);
      Label(&out, x0, y0, pw, p.label);
      DrawText(&out, x0 + 8, y0 + ph / 2, "not available", 2, kLabelInk);
      if (log) log->Add("skip", "panel '" + p.label + "': material not available");
      continue;
    }
    Scene panel_scene = scene;
    for (Object& o : panel_scene.objects) o.material = p.material;
    const Image linear = renderer.RenderLinear(panel_scene, materials, log, pw, ph);
    if (p.material == c.measured) measured_linear = linear;
    if (!c.fitted.empty() && p.material == c.fitted.front()) fitted_linear = linear;
    Blit(renderer.ToDisplay(linear, panel_scene), &out, x0, y0);
    std::string label = p.label;
    if (it->second.kind == MaterialKind::kFactored && it->second.factors) {
      const FactorTextures& f = *it->second.factors;
      label = "factored: " + FactorFormLabel(f.form()) + " " +
              std::to_string(f.terms.empty() ? 0 : f.terms.front().p.width);
    }
    Label(&out, x0, y0, pw, label);
  }
  return out;
}

}  // namespace brdfit::preview
