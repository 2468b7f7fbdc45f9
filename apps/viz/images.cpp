// Pictures of one segmented frame (see images.h): false-colour feature maps, class images and
// bird's-eye views, drawn with OpenCV core/imgproc and written as PNG with libpng.
#include "apps/viz/images.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "host/io/io_error.h"

namespace lpir {
namespace {

// BGR colours: Okabe and Ito's palette for people with any colour vision (docs/decisions/apps.md
// measures each pair's distance under protan, deutan and tritan vision), on black.
const cv::Vec3b kBlack(0, 0, 0);
const cv::Vec3b kWhite(255, 255, 255);
const cv::Vec3b kSkyBlue(0xE9, 0xB4, 0x56);    // #56B4E9: ground
const cv::Vec3b kLightGrey(0x99, 0x99, 0x99);  // #999999: non-ground
const cv::Vec3b kVermilion(0x00, 0x5E, 0xD5);  // #D55E00: wrongly ground, vetoed
const cv::Vec3b kYellow(0x42, 0xE4, 0xF0);     // #F0E442: missed ground, unknown
const cv::Vec3b kOrange(0x00, 0x9F, 0xE6);     // #E69F00: reflection noise
const cv::Vec3b kDarkGrey(0x50, 0x50, 0x50);   // #505050: not scored, unknown off the coarse ground
const cv::Vec3b kBluishGreen(0x73, 0x9E, 0x00);  // #009E73: a bank

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.45;
constexpr int kTextBaseline = 17;  // y of the text baseline inside a legend strip
constexpr int kColorBarWidth = 256;

cv::Scalar ToScalar(const cv::Vec3b& c) { return cv::Scalar(c[0], c[1], c[2]); }

int TextWidth(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, kFontScale, 1, &baseline).width;
}

// Writes `text` at (x, baseline y) in white and returns the x just after it.
int PutText(cv::Mat& image, const std::string& text, int x, int y,
            const cv::Scalar& color = cv::Scalar(255, 255, 255)) {
  cv::putText(image, text, cv::Point(x, y), kFont, kFontScale, color, 1, cv::LINE_AA);
  return x + TextWidth(text);
}

// A 12 x 12 colour swatch with a grey outline (so that black shows on black); returns the x after.
int PutSwatch(cv::Mat& image, const cv::Vec3b& color, int x, int baseline_y) {
  cv::Rect box(x, baseline_y - 11, 12, 12);
  cv::rectangle(image, box, ToScalar(color), cv::FILLED);
  cv::rectangle(image, box, cv::Scalar(128, 128, 128), 1);
  return x + 16;
}

std::string FormatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

// `n` with a comma every three digits: 109,522.
std::string Count(size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

void CheckSize(const char* buffer, size_t have, size_t want) {
  if (have != 0 && have != want) {
    throw std::invalid_argument("WriteImages: frame." + std::string(buffer) + " has " +
                                std::to_string(have) + " entries, expected " +
                                std::to_string(want));
  }
}

// A BGR picture as PNG through libpng's simplified API, not OpenCV's imgcodecs, which loads some
// hundred libraries at every start of the program (docs/decisions/apps.md).
void Write(const std::string& path, const cv::Mat& image, std::vector<std::string>* written) {
  if (image.type() != CV_8UC3)
    throw std::logic_error("WriteImages: a picture that is not 8-bit BGR");
  const cv::Mat pixels = image.isContinuous() ? image : image.clone();
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(pixels.cols);
  png.height = png_uint_32(pixels.rows);
  png.format = PNG_FORMAT_BGR;
  if (!png_image_write_to_file(&png, path.c_str(), 0, pixels.data, png_int_32(pixels.step[0]),
                               nullptr)) {
    const std::string problem = png.message;
    png_image_free(&png);
    throw IoError(path, "cannot write the picture: " + problem);
  }
  written->push_back(path);
}

// ----- range-image pictures -----

// Repeats every row `scale` times (exact, unlike an INTER_NEAREST resize).
cv::Mat RepeatRows(const cv::Mat& image, int scale) {
  cv::Mat out(image.rows * scale, image.cols, image.type());
  for (int r = 0; r < out.rows; ++r) image.row(r / scale).copyTo(out.row(r));
  return out;
}

// The picture rows scaled up, then the legend strip underneath.
cv::Mat WithLegend(const cv::Mat& image, int scale, const cv::Mat& legend) {
  cv::Mat out;
  cv::vconcat(RepeatRows(image, scale), legend, out);
  return out;
}

struct FeatureStyle {
  const char* suffix;  // file name suffix
  const char* title;   // legend text
  const char* unit;
  float lo, hi;    // clipped to this range
  bool log_scale;  // log10 between lo and hi (lo > 0); values <= 0 take the lowest colour
};

// 0..255 position of `v` on the style's colour scale.
uchar Level(float v, const FeatureStyle& style) {
  if (!std::isfinite(v)) return 0;  // drawn white afterwards
  double t;
  if (style.log_scale) {
    if (!(v > 0.0f)) return 0;
    double lo = std::log10(static_cast<double>(style.lo));
    double hi = std::log10(static_cast<double>(style.hi));
    t = (std::log10(static_cast<double>(v)) - lo) / (hi - lo);
  } else {
    t = (static_cast<double>(v) - style.lo) / (static_cast<double>(style.hi) - style.lo);
  }
  t = std::clamp(t, 0.0, 1.0);
  return static_cast<uchar>(std::lround(t * 255.0));
}

cv::Mat FeatureLegend(int width, const FeatureStyle& style) {
  cv::Mat legend(kLegendRows, width, CV_8UC3, cv::Scalar(0, 0, 0));
  std::string title = std::string(style.title) + (style.log_scale ? " (log)" : "");
  int x = PutText(legend, title, 6, kTextBaseline) + 12;
  x = PutText(legend, FormatNumber(style.lo), x, kTextBaseline) + 6;
  cv::Mat ramp(1, kColorBarWidth, CV_8UC1);
  for (int i = 0; i < kColorBarWidth; ++i) ramp.at<uchar>(0, i) = static_cast<uchar>(i);
  cv::Mat ramp_color;
  cv::applyColorMap(ramp, ramp_color, cv::COLORMAP_TURBO);
  for (int r = 6; r < 18; ++r) {
    for (int i = 0; i < kColorBarWidth && x + i < width; ++i) {
      legend.at<cv::Vec3b>(r, x + i) = ramp_color.at<cv::Vec3b>(0, i);
    }
  }
  x += kColorBarWidth + 6;
  x = PutText(legend, FormatNumber(style.hi) + " " + style.unit, x, kTextBaseline) + 24;
  PutText(legend, "black: empty   washed out: hole filled   white: not finite", x, kTextBaseline);
  return legend;
}

// One feature map in false colour: `values` is per pixel, `filled` says which pixels hold one.
cv::Mat FeatureImage(const std::vector<float>& values, const std::vector<uint32_t>& filled,
                     int rows, int cols, const FeatureStyle& style) {
  cv::Mat level(rows, cols, CV_8UC1);
  for (int p = 0; p < rows * cols; ++p)
    level.at<uchar>(p / cols, p % cols) = Level(values[p], style);
  cv::Mat color;
  cv::applyColorMap(level, color, cv::COLORMAP_TURBO);
  for (int p = 0; p < rows * cols; ++p) {
    cv::Vec3b& c = color.at<cv::Vec3b>(p / cols, p % cols);
    if (filled[p] == 0) {
      c = kBlack;
    } else if (!std::isfinite(values[p])) {
      c = kWhite;
    } else if (filled[p] == 2) {
      for (int k = 0; k < 3; ++k) c[k] = static_cast<uchar>((c[k] + 255) / 2);
    }
  }
  return color;
}

// The classes of the class images, in legend order.
const struct PixelClassStyle {
  uint32_t value;
  cv::Vec3b color;
  const char* name;
} kPixelClasses[] = {
    {kPixGround, kSkyBlue, "ground"},  {kPixNonGround, kLightGrey, "non-ground"},
    {kPixUnknown, kYellow, "unknown"}, {kPixUnknownOff, kDarkGrey, "unknown, no coarse ground"},
    {kPixBank, kBluishGreen, "bank"},  {kPixEmpty, kBlack, "empty"},
    {kPixVetoed, kVermilion, "vetoed"}};

// The class's entry of kPixelClasses; the end for a value that is no class.
const PixelClassStyle* StyleOf(uint32_t pixel_class) {
  for (const PixelClassStyle& style : kPixelClasses) {
    if (style.value == pixel_class) return &style;
  }
  return std::end(kPixelClasses);
}

cv::Mat ClassImage(const std::vector<uint32_t>& classes, int rows, int cols) {
  cv::Mat image(rows, cols, CV_8UC3);
  for (int p = 0; p < rows * cols; ++p) {
    const PixelClassStyle* style = StyleOf(classes[p]);
    // not a class: a bug upstream, made visible
    image.at<cv::Vec3b>(p / cols, p % cols) =
        style == std::end(kPixelClasses) ? kWhite : style->color;
  }
  return image;
}

// The title, then each class's swatch, name and pixel count (a value that is no class: white,
// counted when there is one).
cv::Mat ClassLegend(int width, const std::string& title, const std::vector<uint32_t>& classes) {
  std::vector<size_t> counts(std::size(kPixelClasses) + 1, 0);
  for (uint32_t c : classes) ++counts[size_t(StyleOf(c) - kPixelClasses)];
  cv::Mat legend(kLegendRows, width, CV_8UC3, cv::Scalar(0, 0, 0));
  int x = PutText(legend, title, 6, kTextBaseline) + 16;
  for (size_t k = 0; k <= std::size(kPixelClasses); ++k) {
    const bool no_class = k == std::size(kPixelClasses);
    if (no_class && counts[k] == 0) break;
    const cv::Vec3b color = no_class ? kWhite : kPixelClasses[k].color;
    const std::string text =
        std::string(no_class ? "no class" : kPixelClasses[k].name) + " " + Count(counts[k]);
    x = PutText(legend, text, PutSwatch(legend, color, x, kTextBaseline), kTextBaseline) + 16;
  }
  return legend;
}

// ----- bird's-eye views -----

bool IsInvalid(const Frame& frame, size_t i) {
  return (!frame.flags.empty() && !(frame.flags[i] & kPointValid)) ||
         (!frame.why.empty() && frame.why[i] == kWhyInvalid);
}

bool IsNoise(const Frame& frame, size_t i) {
  return (!frame.flags.empty() && (frame.flags[i] & kPointNoise)) ||
         (!frame.why.empty() && frame.why[i] == kWhyNoise);
}

// Point i's category in the legend's order (see BevTally), -1 when invalid.
int BevCategory(const Frame& frame, const std::vector<uint8_t>& predicted,
                const std::vector<uint8_t>* truth, size_t i) {
  if (IsInvalid(frame, i)) return -1;
  const bool ground = predicted[i] == 1;
  if (!truth) return IsNoise(frame, i) ? 2 : (ground ? 1 : 0);
  const uint8_t t = (*truth)[i];
  if (t != 0 && t != 1) return 0;
  if (t == 1) return ground ? 2 : 4;
  return ground ? 3 : 1;
}

struct Category {
  cv::Vec3b color;
  const char* name;
};

// Drawn in this order, so that the rarer (and more interesting) categories end up on top.
const Category kPlainCategories[] = {
    {kLightGrey, "non-ground"}, {kSkyBlue, "ground"}, {kOrange, "reflection noise"}};
const Category kScoredCategories[] = {{kDarkGrey, "not scored"},
                                      {kLightGrey, "TN  non-ground"},
                                      {kSkyBlue, "TP  ground"},
                                      {kVermilion, "FP  wrongly ground"},
                                      {kYellow, "FN  missed ground"}};

// Writes `text` right-aligned to end at x.
void PutTextRight(cv::Mat& image, const std::string& text, int x, int y,
                  const cv::Scalar& color = cv::Scalar(255, 255, 255)) {
  PutText(image, text, x - TextWidth(text), y, color);
}

// `predicted` holds 1 ground / 0 non-ground per point.
cv::Mat BevImage(const Cloud& cloud, const Frame& frame, const std::vector<uint8_t>& predicted,
                 const std::vector<uint8_t>* truth, const std::string& title) {
  cv::Mat image(kBevSize, kBevSize, CV_8UC3, cv::Scalar(0, 0, 0));
  const cv::Point center(kBevSize / 2, kBevSize / 2);
  const float pixels_per_metre = kBevSize / (2.0f * kBevHalfWidth);
  for (int metres = 10; metres <= static_cast<int>(kBevHalfWidth); metres += 10) {
    cv::circle(image, center, static_cast<int>(std::lround(metres * pixels_per_metre)),
               cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
  }

  const Category* categories = truth ? kScoredCategories : kPlainCategories;
  const int num_categories = truth ? 5 : 3;
  for (int c = 0; c < num_categories; ++c) {
    for (size_t i = 0; i < cloud.size(); ++i) {
      int row, col;
      if (BevCategory(frame, predicted, truth, i) != c ||
          !BevPixel(cloud.x(i), cloud.y(i), &row, &col))
        continue;
      for (int dr = 0; dr < 2 && row + dr < kBevSize; ++dr) {
        for (int dc = 0; dc < 2 && col + dc < kBevSize; ++dc) {
          image.at<cv::Vec3b>(row + dr, col + dc) = categories[c].color;
        }
      }
    }
  }
  // The sensor: a small white triangle pointing forward.
  std::vector<cv::Point> sensor = {center + cv::Point(0, -8), center + cv::Point(-5, 6),
                                   center + cv::Point(5, 6)};
  cv::polylines(image, sensor, true, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);

  // Legend, top left: every point counted once, shown or not (outside the view, or invalid).
  const BevTally tally = TallyBev(cloud, frame, predicted, truth);
  const int line = 20;
  const std::string half = std::to_string(static_cast<int>(kBevHalfWidth));
  const std::string heading = title + ", " + Count(cloud.size()) + " points";
  const std::string note = "not shown: beyond " + half + " m, or invalid (NaN, at 0, out of range)";
  const int box_width = std::max({380, TextWidth(heading) + 24, TextWidth(note) + 24});
  const int shown_x = 6 + box_width - 100, not_shown_x = 6 + box_width - 10;
  const cv::Scalar dim(170, 170, 170);
  cv::rectangle(image, cv::Rect(6, 6, box_width, line * (num_categories + 4) + 16),
                cv::Scalar(40, 40, 40), cv::FILLED);
  PutText(image, heading, 14, 6 + line);
  PutTextRight(image, "shown", shown_x, 6 + 2 * line, dim);
  PutTextRight(image, "not shown", not_shown_x, 6 + 2 * line, dim);
  for (int c = 0; c < num_categories; ++c) {
    const int y = 6 + line * (c + 3);
    PutText(image, categories[c].name, PutSwatch(image, categories[c].color, 14, y), y);
    PutTextRight(image, Count(tally.shown[c]), shown_x, y);
    PutTextRight(image, Count(tally.outside[c]), not_shown_x, y);
  }
  const int invalid_y = 6 + line * (num_categories + 3);
  PutText(image, "invalid (non-ground)", PutSwatch(image, kBlack, 14, invalid_y), invalid_y);
  PutTextRight(image, Count(tally.invalid), not_shown_x, invalid_y);
  PutText(image, note, 14, invalid_y + line, dim);
  PutText(image, "x forward = up, rings every 10 m, +-" + half + " m shown", 10, kBevSize - 10,
          cv::Scalar(160, 160, 160));
  return image;
}

}  // namespace

BevTally TallyBev(const Cloud& cloud, const Frame& frame, const std::vector<uint8_t>& predicted,
                  const std::vector<uint8_t>* truth) {
  BevTally tally;
  tally.shown.assign(truth ? 5 : 3, 0);
  tally.outside.assign(truth ? 5 : 3, 0);
  for (size_t i = 0; i < cloud.size(); ++i) {
    const int c = BevCategory(frame, predicted, truth, i);
    int row, col;
    if (c < 0) {
      ++tally.invalid;
    } else if (BevPixel(cloud.x(i), cloud.y(i), &row, &col)) {
      ++tally.shown[c];
    } else {
      ++tally.outside[c];
    }
  }
  return tally;
}

int RangeImageRowScale(uint32_t beams) {
  if (beams == 0) return 1;
  return static_cast<int>(std::clamp<uint32_t>((256 + beams - 1) / beams, 1, 16));
}

bool BevPixel(float x, float y, int* row, int* col) {
  const float pixels_per_metre = kBevSize / (2.0f * kBevHalfWidth);
  float r = (kBevHalfWidth - x) * pixels_per_metre;
  float c = (kBevHalfWidth - y) * pixels_per_metre;
  if (!(r >= 0.0f && r < static_cast<float>(kBevSize) && c >= 0.0f &&
        c < static_cast<float>(kBevSize))) {
    return false;  // outside, or not finite
  }
  *row = static_cast<int>(r);
  *col = static_cast<int>(c);
  return true;
}

std::vector<std::string> WriteImages(const std::string& dir, const std::string& stem,
                                     const Cloud& cloud, const Frame& frame, const Params& params,
                                     const std::vector<uint8_t>* truth) {
  const size_t n = cloud.size();
  if (frame.n != n) {
    throw std::invalid_argument("WriteImages: the frame has " + std::to_string(frame.n) +
                                " points, the cloud " + std::to_string(n));
  }
  if (params.width == 0 || params.beams == 0) {
    throw std::invalid_argument("WriteImages: params.width and params.beams must be positive");
  }
  const int rows = static_cast<int>(params.beams);
  const int cols = static_cast<int>(params.width);
  const size_t pixels = static_cast<size_t>(rows) * cols;
  ForEachBuffer(
      [&](const BufferInfo& info, const auto& buffer) {
        CheckSize(info.name, buffer.size(), ItemsOf(info.per, n, params) * info.stride);
      },
      frame);
  if (truth && truth->size() != n) {
    throw std::invalid_argument("WriteImages: the truth has " + std::to_string(truth->size()) +
                                " labels, the cloud " + std::to_string(n) + " points");
  }

  if (!dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (!std::filesystem::is_directory(dir)) {
      throw IoError(dir, "cannot create the folder for the pictures" +
                             (ec ? ": " + ec.message() : std::string()));
    }
  }
  const std::string prefix = (dir.empty() ? std::string() : dir + "/") + stem + "_";
  const int scale = RangeImageRowScale(params.beams);
  std::vector<std::string> written;

  // Feature maps. Ranges are fixed so that pictures of different frames compare; the height
  // scale starts 1 m under the road (z_t is relative to the sensor) and spans 4 m.
  const float h =
      params.sensor_height > 0.0f && params.sensor_height < 10.0f ? params.sensor_height : 0.0f;
  const float height_lo = h > 0.0f ? -h - 1.0f : -3.0f;
  const float height_hi = h > 0.0f ? -h + 3.0f : 3.0f;
  std::vector<float> edge;
  if (!frame.f_edge_l.empty() || !frame.f_edge_r.empty()) {
    const std::vector<float>& l = frame.f_edge_l.empty() ? frame.f_edge_r : frame.f_edge_l;
    const std::vector<float>& r = frame.f_edge_r.empty() ? frame.f_edge_l : frame.f_edge_r;
    edge.resize(pixels);
    for (size_t p = 0; p < pixels; ++p) edge[p] = std::max(l[p], r[p]);
  }
  const struct {
    const std::vector<float>* values;
    FeatureStyle style;
  } features[] = {
      {&frame.f_range, {"range", "range", "m", 0.0f, 80.0f, false}},
      {&frame.f_height, {"height", "height z_t", "m", height_lo, height_hi, false}},
      {&frame.f_slope, {"slope", "slope |dz|/|dr|", "", 0.0f, 2.0f, false}},
      {&edge, {"edge", "edge max(left, right)", "m", 0.0f, 1.0f, false}},
      {&frame.f_varz, {"varz", "height variance 3x3", "m^2", 1e-5f, 1.0f, true}},
  };
  if (!frame.pixel_filled.empty()) {
    for (const auto& f : features) {
      if (f.values->empty()) continue;
      cv::Mat image = FeatureImage(*f.values, frame.pixel_filled, rows, cols, f.style);
      Write(prefix + f.style.suffix + ".png",
            WithLegend(image, scale, FeatureLegend(cols, f.style)), &written);
    }
  }

  const struct {
    const std::vector<uint32_t>* classes;
    const char* suffix;
    const char* title;
  } class_images[] = {
      {&frame.pixel_class, "classes", "pixel classes (eqs. 8-12)"},
      {&frame.pixel_fused, "fused", "fused with the coarse labels"},
      {&frame.pixel_label, "labels", "final pixel labels"},
  };
  for (const auto& c : class_images) {
    if (c.classes->empty()) continue;
    Write(prefix + c.suffix + ".png",
          WithLegend(ClassImage(*c.classes, rows, cols), scale,
                     ClassLegend(cols, c.title, *c.classes)),
          &written);
  }

  if (!frame.label.empty()) {
    Write(prefix + "bev.png", BevImage(cloud, frame, frame.label, truth, stem + ": final labels"),
          &written);
  }
  if (!frame.coarse.empty()) {
    std::vector<uint8_t> coarse(n);
    for (size_t i = 0; i < n; ++i) coarse[i] = frame.coarse[i] == 1 ? 1 : 0;
    Write(prefix + "coarse_bev.png",
          BevImage(cloud, frame, coarse, truth, stem + ": coarse stage only"), &written);
  }
  return written;
}

}  // namespace lpir

// The entry point that lpir-gseg looks up in this library (apps/viz/images_loader.cpp): WriteImages
// under a name without C++ mangling, its result through *written (a C-linkage function returns
// no C++ type).
extern "C" void lpir_write_images(const std::string& dir, const std::string& stem,
                                  const lpir::Cloud& cloud, const lpir::Frame& frame,
                                  const lpir::Params& params, const std::vector<uint8_t>* truth,
                                  std::vector<std::string>* written) {
  *written = lpir::WriteImages(dir, stem, cloud, frame, params, truth);
}
