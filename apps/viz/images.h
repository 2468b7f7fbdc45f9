// Pictures of one segmented frame: every feature map in false colour, the pixel classes before and
// after fusion, the final label image, and bird's-eye views of the coarse and the final labels
// (optionally scored against ground truth, the paper's Fig. 7, in colours that people with any
// colour vision tell apart). For people, not tests of the method: nothing here feeds back into
// the pipeline.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "shaders/common/params.h"

namespace lpir {

// Truth value of a point that is not scored (drawn dark grey in the bird's-eye views).
constexpr uint8_t kTruthNotScored = 255;

// Range-image pictures are params.width columns (full width) and
// params.beams * RangeImageRowScale(params.beams) + kLegendRows rows: every beam row repeated
// (nearest neighbour) so that the image is about 256 rows tall, then a legend strip underneath.
constexpr int kLegendRows = 24;
int RangeImageRowScale(uint32_t beams);

// Bird's-eye views are kBevSize x kBevSize pixels covering kBevHalfWidth metres on each side of
// the sensor, x (forward) up and y (left) to the left. A point is a 2 x 2 dot whose top-left pixel
// is BevPixel(x, y); false when the point lies outside the view.
constexpr int kBevSize = 1000;
constexpr float kBevHalfWidth = 50.0f;
bool BevPixel(float x, float y, int* row, int* col);

// The scored bird's-eye view's colours in words, for messages: "TP sky blue, TN grey, ...".
inline constexpr char kScoredColours[] = "TP sky blue, TN grey, FP vermilion, FN yellow";

// What a bird's-eye view's legend counts: per category in the legend's order (without truth:
// non-ground, ground, reflection noise; with truth: not scored, TN, TP, FP, FN), the points drawn
// and those outside the view; and the invalid points (flags or why say so), never drawn. Every
// point of the cloud is counted once. `predicted`: 1 ground, 0 non-ground per point; `truth` as
// WriteImages takes it, or null.
struct BevTally {
  std::vector<size_t> shown, outside;
  size_t invalid = 0;
};
BevTally TallyBev(const Cloud& cloud, const Frame& frame, const std::vector<uint8_t>& predicted,
                  const std::vector<uint8_t>* truth);

// Writes every picture whose buffers the frame holds into `dir` (created when missing), as
// <dir>/<stem>_<name>.png, and returns the paths written, in this order:
//   _range, _intensity, _height, _slope, _edge (max of left and right), _varz, _vari
//       feature maps in false colour (turbo) over fixed ranges; black = empty pixel, washed out =
//       hole filled by morphology, white = not a finite number.
//   _classes, _fused, _labels
//       pixel_class, pixel_fused, pixel_label in Okabe and Ito's colours: ground sky blue,
//       non-ground grey, unknown yellow, empty black, vetoed vermilion (pixel_fused only); the
//       legend counts the pixels of each class.
//   _bev, _coarse_bev
//       bird's-eye views of frame.label and of frame.coarse, on black. Without truth: ground sky
//       blue, non-ground light grey, reflection noise orange. With truth (one entry per point:
//       1 ground, 0 non-ground, kTruthNotScored): TP sky blue, TN light grey, FP vermilion,
//       FN yellow, not scored dark grey. Invalid points are not drawn; the legend gives
//       TallyBev's counts, so every point is counted, shown or not.
// A picture is left out when a buffer it needs is empty (a backend that kept only the labels).
// Throws std::invalid_argument when a non-empty buffer has the wrong size, and lpir::IoError
// (a std::runtime_error naming the path) when a folder or file cannot be written.
std::vector<std::string> WriteImages(const std::string& dir, const std::string& stem,
                                     const Cloud& cloud, const Frame& frame, const Params& params,
                                     const std::vector<uint8_t>* truth);

// The pictures live in their own library, liblpir_images.so (OpenCV's drawing and its dependencies,
// some twenty libraries that take milliseconds to load), which the command-line program loads only
// when asked for pictures (apps/viz/images_loader.cpp): LoadImages loads it from the program's
// folder, once; it throws std::runtime_error naming the file and the loader's reason when it
// cannot. The program's WriteImages calls LoadImages, then the library's.
void LoadImages();

}  // namespace lpir
