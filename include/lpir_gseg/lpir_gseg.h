// lpir-gseg's public header: all that a program needs to label the points of LiDAR scans.
//   LoadSensorProfile(name or path)    a sensor profile; names are looked up in DefaultSensorsDir()
//   Segmenter, SegmenterOptions        made once per sensor; Segment(cloud) labels one cloud on
//                                      Vulkan or the CPU reference, the same bytes either way
//   Cloud, ReadCloud(path)             a scan: KITTI .bin, nuScenes .pcd.bin, .pcd, .ply
//   Frame::label, Frame::why, kWhy*    per point: 1 ground, 0 non-ground; why it got that label
//   WriteLabelFile, ReadLabelFile      SemanticKITTI .label files (uint32 per point)
//   IoError                            what every reader and writer throws, naming the file
// With CMake: find_package(lpir_gseg) and link lpir_gseg::lpir_gseg (C++17; docs/usage.md).
#pragma once

#include "host/api/segmenter.h"
#include "host/io/cloud_file.h"
#include "host/io/io_error.h"
#include "host/io/label_file.h"
#include "host/io/sensor_profile.h"
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
