// segment_file SCAN SENSOR OUT.label [auto|cpu|vulkan]: labels every point of one scan (KITTI
// .bin, nuScenes .pcd.bin, .pcd or .ply) with a sensor profile (a name, looked up in the installed
// profiles, or a file) and writes OUT.label as `lpir-gseg segment` does: a little-endian uint32
// per point, 1 ground, 0 non-ground. The backend defaults to auto (a GPU, else the CPU
// reference); the labels are the same bytes on either.
#include <lpir_gseg/lpir_gseg.h>

#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: %s SCAN SENSOR OUT.label [auto|cpu|vulkan]\n", argv[0]);
    return 2;
  }
  try {
    const lpir::Cloud cloud = lpir::ReadCloud(argv[1]);
    lpir::SegmenterOptions options;
    options.backend = lpir::ParseBackend(argc == 5 ? argv[4] : "auto");
    lpir::Segmenter segmenter(lpir::LoadSensorProfile(argv[2]), options);
    const lpir::Frame& frame = segmenter.Segment(cloud);
    const std::vector<uint32_t> labels(frame.label.begin(), frame.label.end());
    lpir::WriteLabelFile(argv[3], labels);
    size_t ground = 0;
    for (uint8_t label : frame.label) ground += label;
    std::printf("%s: %zu points, %zu ground, on %s\n", argv[1], cloud.size(), ground,
                segmenter.backend_note().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", argv[0], e.what());
    return 1;
  }
  return 0;
}
