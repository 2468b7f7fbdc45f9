// Tests of the pictures (apps/viz/images.h) on a small hand-made frame: which files are written,
// their sizes, the colours of chosen pixels and how far apart they look to people with each kind
// of colour vision, the legend's counts, skipped buffers and the errors.
#include "apps/viz/images.h"

#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/test_util.h"

namespace lpir {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kBeams = 4;
constexpr uint32_t kWidth = 64;
constexpr uint32_t kPixels = kBeams * kWidth;

// BGR: black, white, and Okabe and Ito's colours the pictures use.
const cv::Vec3b kBlack(0, 0, 0), kWhite(255, 255, 255), kSkyBlue(0xE9, 0xB4, 0x56),
    kLightGrey(0x99, 0x99, 0x99), kVermilion(0x00, 0x5E, 0xD5), kYellow(0x42, 0xE4, 0xF0),
    kOrange(0x00, 0x9F, 0xE6), kDarkGrey(0x50, 0x50, 0x50);

Params SmallParams() {
  Params p{};
  p.width = kWidth;
  p.beams = kBeams;
  p.sensor_height = 1.73f;
  return p;
}

// The turbo colour of level 0..255, as the pictures draw it.
cv::Vec3b Turbo(int level) {
  cv::Mat one(1, 1, CV_8UC1, cv::Scalar(level));
  cv::Mat color;
  cv::applyColorMap(one, color, cv::COLORMAP_TURBO);
  return color.at<cv::Vec3b>(0, 0);
}

// Points and their truth; every point's role is fixed by its index (see the comments).
struct Scene {
  Cloud cloud;
  Frame frame;
  std::vector<uint8_t> truth;
};

Scene MakeScene() {
  Scene s;
  // x, y, z, intensity / flags / final label / coarse label / why / truth
  struct P {
    float x, y;
    uint32_t flags;
    uint8_t label, coarse, why, truth;
  } points[] = {
      {10, 0, kPointValid, 1, 1, kWhyGround, 1},                  // 0 TP
      {0, 10, kPointValid, 0, 1, kWhyNonGround, 1},               // 1 FN (coarse: TP)
      {-10, 0, kPointValid, 1, 0, kWhyGround, 0},                 // 2 FP (coarse: TN)
      {0, -10, kPointValid, 0, 0, kWhyNonGround, 0},              // 3 TN
      {20, 20, kPointValid, 1, 1, kWhyGround, kTruthNotScored},   // 4 not scored
      {5, 5, 0, 0, 0, kWhyInvalid, 1},                            // 5 invalid
      {-20, -20, kPointValid | kPointNoise, 0, 0, kWhyNoise, 0},  // 6 noise, TN
      {80, 0, kPointValid, 1, 1, kWhyGround, 1},                  // 7 outside the view
  };
  for (const P& p : points) {
    s.cloud.Push(p.x, p.y, -1.7f, 0.3f);
    s.frame.flags.push_back(p.flags);
    s.frame.label.push_back(p.label);
    s.frame.coarse.push_back(p.coarse);
    s.frame.why.push_back(p.why);
    s.truth.push_back(p.truth);
  }
  Frame& f = s.frame;
  f.n = static_cast<uint32_t>(s.cloud.size());
  f.pixel_filled.assign(kPixels, 1);
  f.pixel_filled[0] = 0;  // empty
  f.pixel_filled[2] = 2;  // hole filled
  for (auto* feature : {&f.f_range, &f.f_height, &f.f_slope, &f.f_edge_l, &f.f_edge_r, &f.f_varz}) {
    feature->assign(kPixels, 0.0f);
  }
  f.f_range[1] = 80.0f;   // top of the range scale
  f.f_range[2] = 80.0f;   // the same, hole filled
  f.f_range[3] = 0.0f;    // bottom
  f.f_range[4] = 500.0f;  // clipped to the top
  f.f_range[5] = std::numeric_limits<float>::quiet_NaN();
  f.f_edge_l[1] = 1.0f;  // edge = max(left, right)
  f.f_edge_r[3] = 1.0f;
  f.f_varz[1] = 1.0f;  // log scale: 1 m^2 is the top, 1e-5 and below (and 0) the bottom
  f.f_varz[3] = 1e-7f;
  f.pixel_class.assign(kPixels, kPixNonGround);
  f.pixel_class[kWidth + 5] = kPixGround;  // row 1, column 5
  f.pixel_class[kWidth + 6] = kPixUnknown;
  f.pixel_class[kWidth + 7] = kPixEmpty;
  f.pixel_fused = f.pixel_class;
  f.pixel_fused[kWidth + 5] = kPixUnknown;
  f.pixel_label.assign(kPixels, kPixNonGround);
  f.pixel_label[2 * kWidth + 9] = kPixGround;
  f.pixel_label[2 * kWidth + 10] = kPixEmpty;
  return s;
}

// Pixel (row, col) of the range image, in the picture (rows repeated, legend below).
cv::Vec3b RangePixel(const cv::Mat& image, int row, int col) {
  int scale = RangeImageRowScale(kBeams);
  // Every repeated row holds the same colour.
  for (int k = 1; k < scale; ++k) {
    EXPECT_EQ(image.at<cv::Vec3b>(row * scale + k, col), image.at<cv::Vec3b>(row * scale, col));
  }
  return image.at<cv::Vec3b>(row * scale, col);
}

cv::Vec3b BevColor(const cv::Mat& image, float x, float y) {
  int row = -1, col = -1;
  EXPECT_TRUE(BevPixel(x, y, &row, &col)) << x << ", " << y;
  return image.at<cv::Vec3b>(row, col);
}

// A PNG as 8-bit BGR (libpng's simplified API converts any PNG to that); empty when unreadable.
cv::Mat Read(const std::string& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  cv::Mat image;
  if (png_image_begin_read_from_file(&png, path.c_str())) {
    png.format = PNG_FORMAT_BGR;
    image.create(int(png.height), int(png.width), CV_8UC3);
    if (!png_image_finish_read(&png, nullptr, image.data, png_int_32(image.step[0]), nullptr))
      image.release();
  }
  EXPECT_FALSE(image.empty()) << path << ": " << png.message;
  png_image_free(&png);
  return image;
}

TEST(Images, BevPixelGeometry) {
  int row, col;
  ASSERT_TRUE(BevPixel(10.0f, 0.0f, &row, &col));  // forward is up
  EXPECT_EQ(row, 400);
  EXPECT_EQ(col, 500);
  ASSERT_TRUE(BevPixel(0.0f, 10.0f, &row, &col));  // left is left
  EXPECT_EQ(row, 500);
  EXPECT_EQ(col, 400);
  ASSERT_TRUE(BevPixel(50.0f, 50.0f, &row, &col));  // the top-left corner
  EXPECT_EQ(row, 0);
  EXPECT_EQ(col, 0);
  EXPECT_FALSE(BevPixel(-50.0f, 0.0f, &row, &col));  // 1000 rows: x in (-50, 50]
  EXPECT_FALSE(BevPixel(0.0f, -50.0f, &row, &col));
  EXPECT_FALSE(BevPixel(50.1f, 0.0f, &row, &col));
  EXPECT_TRUE(BevPixel(-49.9f, -49.9f, &row, &col));
  EXPECT_FALSE(BevPixel(std::nanf(""), 0.0f, &row, &col));
  EXPECT_EQ(RangeImageRowScale(64), 4);
  EXPECT_EQ(RangeImageRowScale(128), 2);
  EXPECT_EQ(RangeImageRowScale(16), 16);
  EXPECT_EQ(RangeImageRowScale(4), 16);  // at most 16
}

TEST(Images, WritesEveryPictureWithTheExpectedColours) {
  Scene s = MakeScene();
  const std::string dir = test::TempDir() + "/pictures";  // created by WriteImages
  std::vector<std::string> paths =
      WriteImages(dir, "f0", s.cloud, s.frame, SmallParams(), &s.truth);

  const std::vector<std::string> names = {"range",   "height", "slope",  "edge", "varz",
                                          "classes", "fused",  "labels", "bev",  "coarse_bev"};
  ASSERT_EQ(paths.size(), names.size());
  const int range_rows = static_cast<int>(kBeams) * RangeImageRowScale(kBeams) + kLegendRows;
  for (size_t i = 0; i < names.size(); ++i) {
    EXPECT_EQ(paths[i], dir + "/f0_" + names[i] + ".png");
    ASSERT_TRUE(fs::is_regular_file(paths[i])) << paths[i];
    cv::Mat image = Read(paths[i]);
    bool bev = names[i].find("bev") != std::string::npos;
    EXPECT_EQ(image.cols, bev ? kBevSize : static_cast<int>(kWidth)) << paths[i];
    EXPECT_EQ(image.rows, bev ? kBevSize : range_rows) << paths[i];
  }

  // Feature maps: empty black, clipped ranges, NaN white, hole filled washed out.
  cv::Mat range = Read(dir + "/f0_range.png");
  EXPECT_EQ(RangePixel(range, 0, 0), kBlack);
  EXPECT_EQ(RangePixel(range, 0, 1), Turbo(255));
  EXPECT_EQ(RangePixel(range, 0, 3), Turbo(0));
  EXPECT_EQ(RangePixel(range, 0, 4), Turbo(255));
  EXPECT_EQ(RangePixel(range, 0, 5), kWhite);
  cv::Vec3b top = Turbo(255), pale = RangePixel(range, 0, 2);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(pale[k], (top[k] + 255) / 2);
  cv::Mat edge = Read(dir + "/f0_edge.png");
  EXPECT_EQ(RangePixel(edge, 0, 1), Turbo(255));  // from the left edge
  EXPECT_EQ(RangePixel(edge, 0, 3), Turbo(255));  // from the right edge
  EXPECT_EQ(RangePixel(edge, 0, 6), Turbo(0));
  cv::Mat varz = Read(dir + "/f0_varz.png");
  EXPECT_EQ(RangePixel(varz, 0, 1), Turbo(255));
  EXPECT_EQ(RangePixel(varz, 0, 3), Turbo(0));
  EXPECT_EQ(RangePixel(varz, 0, 6), Turbo(0));  // zero variance on a log scale
  // The legend strip holds something (text, colour bar) below the picture.
  EXPECT_GT(cv::countNonZero(range.rowRange(range_rows - kLegendRows, range_rows).reshape(1)), 0);

  // Class images.
  cv::Mat classes = Read(dir + "/f0_classes.png");
  EXPECT_EQ(RangePixel(classes, 1, 5), kSkyBlue);
  EXPECT_EQ(RangePixel(classes, 1, 6), kYellow);
  EXPECT_EQ(RangePixel(classes, 1, 7), kBlack);
  EXPECT_EQ(RangePixel(classes, 1, 8), kLightGrey);
  EXPECT_EQ(RangePixel(Read(dir + "/f0_fused.png"), 1, 5), kYellow);
  cv::Mat labels = Read(dir + "/f0_labels.png");
  EXPECT_EQ(RangePixel(labels, 2, 9), kSkyBlue);
  EXPECT_EQ(RangePixel(labels, 2, 10), kBlack);
  EXPECT_EQ(RangePixel(labels, 3, 9), kLightGrey);

  // Bird's-eye views scored against the truth: the paper's Fig. 7 classes.
  cv::Mat bev = Read(dir + "/f0_bev.png");
  EXPECT_EQ(BevColor(bev, 10, 0), kSkyBlue);       // TP
  EXPECT_EQ(BevColor(bev, 0, 10), kYellow);        // FN
  EXPECT_EQ(BevColor(bev, -10, 0), kVermilion);    // FP
  EXPECT_EQ(BevColor(bev, 0, -10), kLightGrey);    // TN
  EXPECT_EQ(BevColor(bev, 20, 20), kDarkGrey);     // not scored
  EXPECT_EQ(BevColor(bev, 5, 5), kBlack);          // invalid: not drawn
  EXPECT_EQ(BevColor(bev, -20, -20), kLightGrey);  // noise, rightly non-ground
  int row, col;
  ASSERT_TRUE(BevPixel(10, 0, &row, &col));
  EXPECT_EQ(bev.at<cv::Vec3b>(row + 1, col + 1), kSkyBlue);  // dots are 2 x 2
  // The legend (top left) is drawn.
  EXPECT_GT(cv::countNonZero(bev(cv::Rect(0, 0, 340, 140)).reshape(1)), 0);
  cv::Mat coarse = Read(dir + "/f0_coarse_bev.png");
  EXPECT_EQ(BevColor(coarse, 0, 10), kSkyBlue);  // the coarse stage had it right
  EXPECT_EQ(BevColor(coarse, -10, 0), kLightGrey);
  EXPECT_EQ(BevColor(coarse, 10, 0), kSkyBlue);
}

TEST(Images, WithoutTruthColoursByLabel) {
  Scene s = MakeScene();
  const std::string dir = test::TempDir();
  WriteImages(dir, "plain", s.cloud, s.frame, SmallParams(), nullptr);
  cv::Mat bev = Read(dir + "/plain_bev.png");
  EXPECT_EQ(BevColor(bev, 10, 0), kSkyBlue);    // ground
  EXPECT_EQ(BevColor(bev, 0, 10), kLightGrey);  // non-ground
  EXPECT_EQ(BevColor(bev, -20, -20), kOrange);  // reflection noise
  EXPECT_EQ(BevColor(bev, 5, 5), kBlack);       // invalid
  cv::Mat coarse = Read(dir + "/plain_coarse_bev.png");
  EXPECT_EQ(BevColor(coarse, 0, 10), kSkyBlue);
  EXPECT_EQ(BevColor(coarse, -10, 0), kLightGrey);
}

TEST(Images, TheLegendsTallyCountsEveryPointOnce) {
  Scene s = MakeScene();
  // Scored: not scored 4; TN 3 and the noise 6; TP 0, and 7 beyond the view; FP 2; FN 1.
  const BevTally scored = TallyBev(s.cloud, s.frame, s.frame.label, &s.truth);
  EXPECT_EQ(scored.shown, (std::vector<size_t>{1, 2, 1, 1, 1}));
  EXPECT_EQ(scored.outside, (std::vector<size_t>{0, 0, 1, 0, 0}));
  EXPECT_EQ(scored.invalid, 1u);  // point 5
  // Plain: non-ground 1 and 3; ground 0, 2, 4, and 7 beyond; noise 6.
  const BevTally plain = TallyBev(s.cloud, s.frame, s.frame.label, nullptr);
  EXPECT_EQ(plain.shown, (std::vector<size_t>{2, 3, 1}));
  EXPECT_EQ(plain.outside, (std::vector<size_t>{0, 1, 0}));
  EXPECT_EQ(plain.invalid, 1u);
  // The coarse labels: point 1 ground, 2 not.
  const std::vector<uint8_t> coarse_labels(s.frame.coarse.begin(), s.frame.coarse.end());
  const BevTally coarse = TallyBev(s.cloud, s.frame, coarse_labels, &s.truth);
  EXPECT_EQ(coarse.shown, (std::vector<size_t>{1, 3, 2, 0, 0}));
}

// CIELAB of an sRGB colour (BGR) as a person with `vision` sees it: Machado, Oliveira and
// Fernandes (2009) at full severity, applied to linear RGB.
cv::Vec3d LabAs(const cv::Vec3b& bgr, int vision) {
  static const double kMatrices[4][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                            {{0.152286, 1.052583, -0.204868},
                                             {0.114503, 0.786281, 0.099216},
                                             {-0.003882, -0.048116, 1.051998}},  // protanopia
                                            {{0.367322, 0.860646, -0.227968},
                                             {0.280085, 0.672501, 0.047413},
                                             {-0.011820, 0.042940, 0.968881}},  // deuteranopia
                                            {{1.255528, -0.076749, -0.178779},
                                             {-0.078411, 0.930809, 0.147602},
                                             {0.004733, 0.691367, 0.303900}}};  // tritanopia
  double rgb[3];
  for (int k = 0; k < 3; ++k) {
    const double c = bgr[2 - k] / 255.0;
    rgb[k] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  }
  double seen[3];
  for (int r = 0; r < 3; ++r) {
    seen[r] = 0;
    for (int k = 0; k < 3; ++k) seen[r] += kMatrices[vision][r][k] * rgb[k];
    seen[r] = std::clamp(seen[r], 0.0, 1.0);
  }
  const double xyz[3] = {(0.4124 * seen[0] + 0.3576 * seen[1] + 0.1805 * seen[2]) / 0.95047,
                         0.2126 * seen[0] + 0.7152 * seen[1] + 0.0722 * seen[2],
                         (0.0193 * seen[0] + 0.1192 * seen[1] + 0.9505 * seen[2]) / 1.08883};
  double f[3];
  for (int k = 0; k < 3; ++k) {
    f[k] = xyz[k] > 216.0 / 24389.0 ? std::cbrt(xyz[k]) : xyz[k] * 841.0 / 108.0 + 4.0 / 29.0;
  }
  return {116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])};
}

TEST(Images, ScoredColoursStayApartForEveryColourVision) {
  Scene s = MakeScene();
  const std::string dir = test::TempDir();
  WriteImages(dir, "cv", s.cloud, s.frame, SmallParams(), &s.truth);
  const cv::Mat bev = Read(dir + "/cv_bev.png");
  // TP, FN, FP, TN, not scored and the background, as drawn.
  const std::vector<cv::Vec3b> drawn = {BevColor(bev, 10, 0),  BevColor(bev, 0, 10),
                                        BevColor(bev, -10, 0), BevColor(bev, 0, -10),
                                        BevColor(bev, 20, 20), BevColor(bev, 5, 5)};
  for (int vision = 0; vision < 4; ++vision) {
    for (size_t a = 0; a < drawn.size(); ++a) {
      for (size_t b = a + 1; b < drawn.size(); ++b) {
        // 20 CIELAB units: told apart at a glance (the old green/yellow pair was 8 for protans)
        EXPECT_GE(cv::norm(LabAs(drawn[a], vision) - LabAs(drawn[b], vision)), 20.0)
            << "vision " << vision << ": colours " << a << " and " << b;
      }
    }
  }
}

TEST(Images, LeavesOutPicturesWhoseBuffersAreEmpty) {
  Scene s = MakeScene();
  Frame only_labels;
  only_labels.n = s.frame.n;
  only_labels.label = s.frame.label;
  only_labels.why = s.frame.why;
  const std::string dir = test::TempDir();
  std::vector<std::string> paths =
      WriteImages(dir, "x", s.cloud, only_labels, SmallParams(), nullptr);
  ASSERT_EQ(paths.size(), 1u);
  EXPECT_EQ(paths[0], dir + "/x_bev.png");
  EXPECT_EQ(BevColor(Read(paths[0]), 0, 10), kLightGrey);
}

TEST(Images, RejectsInconsistentBuffers) {
  Scene s = MakeScene();
  const std::string dir = test::TempDir();
  Frame bad = s.frame;
  bad.f_slope.pop_back();
  try {
    WriteImages(dir, "bad", s.cloud, bad, SmallParams(), nullptr);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("f_slope"), std::string::npos) << e.what();
  }
  std::vector<uint8_t> short_truth(s.truth.begin(), s.truth.end() - 1);
  EXPECT_THROW(WriteImages(dir, "bad", s.cloud, s.frame, SmallParams(), &short_truth),
               std::invalid_argument);
  Cloud more = s.cloud;
  more.Push(1, 1, 1, 1);
  EXPECT_THROW(WriteImages(dir, "bad", more, s.frame, SmallParams(), nullptr),
               std::invalid_argument);
}

TEST(Images, UnwritableFolderThrowsNamingThePath) {
  Scene s = MakeScene();
  // A regular file where a folder should be: no one (root included) can create the folder.
  const std::string file = test::TempDir() + "/not_a_folder";
  std::ofstream(file) << "x";
  const std::string dir = file + "/pictures";
  try {
    WriteImages(dir, "f", s.cloud, s.frame, SmallParams(), nullptr);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir), std::string::npos) << e.what();
  }
}

TEST(Images, UnwritableFileThrowsNamingThePath) {
  Scene s = MakeScene();
  const std::string dir = test::TempDir();
  // A folder where the picture should go: the PNG cannot be written (whoever runs the test).
  const std::string path = dir + "/f_range.png";
  fs::create_directories(path);
  try {
    WriteImages(dir, "f", s.cloud, s.frame, SmallParams(), nullptr);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lpir
