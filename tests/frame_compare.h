// Byte comparison of two whole frames (every buffer of every stage, reference_cpu/frame.h), for
// the tests that run the full pipeline on both backends. A mismatch names the stage, the buffer,
// the first differing element, both values in decimal and hex, and the point, pixel (u, v) or
// cell the element belongs to.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir::test {

template <typename T>
std::string ElementText(T value) {
  char text[64];
  uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(T) < 4 ? sizeof(T) : 4);
  if constexpr (sizeof(T) == 4 && std::is_floating_point_v<T>)
    std::snprintf(text, sizeof(text), "%.9g (0x%08x)", double(value), bits);
  else if constexpr (std::is_signed_v<T>)
    std::snprintf(text, sizeof(text), "%d (0x%08x)", int(value), bits);
  else
    std::snprintf(text, sizeof(text), "%u (0x%0*x)", unsigned(value), int(2 * sizeof(T)), bits);
  return text;
}

enum class Per { kPoint, kPixel, kCell };

// Compares one buffer; returns the number of bytes compared (0 on a size mismatch).
template <typename T>
uint64_t ExpectSameBuffer(const char* stage, const char* buffer, Per per, uint32_t stride,
                          const std::vector<T>& cpu, const std::vector<T>& gpu, const Params& p,
                          const Cloud* cloud, const std::string& what) {
  EXPECT_EQ(gpu.size(), cpu.size()) << what << ": " << stage << " buffer " << buffer << " size";
  if (gpu.size() != cpu.size()) return 0;
  size_t first = cpu.size(), count = 0;
  for (size_t i = 0; i < cpu.size(); ++i)
    if (std::memcmp(&cpu[i], &gpu[i], sizeof(T)) != 0) {
      if (first == cpu.size()) first = i;
      ++count;
    }
  if (count != 0) {
    const size_t item = first / stride;
    std::string where;
    if (per == Per::kPixel) {
      where = "pixel (u " + std::to_string(item % p.width) + ", v " +
              std::to_string(item / p.width) + ")";
    } else if (per == Per::kCell) {
      where = "cell " + std::to_string(item) + " (word " + std::to_string(first % stride) + ")";
    } else {
      where = "point " + std::to_string(item);
      if (cloud && item < cloud->size())
        where += " (x " + ElementText(cloud->x(item)) + ", y " + ElementText(cloud->y(item)) +
                 ", z " + ElementText(cloud->z(item)) + ")";
    }
    ADD_FAILURE() << what << ": stage " << stage << ", buffer " << buffer << " differs first at "
                  << "element " << first << " (" << count << " of " << cpu.size()
                  << " differ): CPU " << ElementText(cpu[first]) << ", GPU "
                  << ElementText(gpu[first]) << "; " << where;
  }
  return uint64_t(cpu.size()) * sizeof(T);
}

// Every buffer of the two frames; returns the bytes compared.
inline uint64_t ExpectSameFrame(const Params& p, const Frame& cpu, const Frame& gpu,
                                const Cloud* cloud, const std::string& what) {
  EXPECT_EQ(gpu.n, cpu.n) << what << ": point count";
  uint64_t bytes = 0;
  const Per pt = Per::kPoint, px = Per::kPixel, cell = Per::kCell;
  auto same = [&](const char* stage, const char* name, Per per, const auto& a, const auto& b,
                  uint32_t stride = 1) {
    bytes += ExpectSameBuffer(stage, name, per, stride, a, b, p, cloud, what);
  };
  same("prepare", "flags", pt, cpu.flags, gpu.flags);
  same("prepare", "zt", pt, cpu.zt, gpu.zt);
  same("prepare", "r2", pt, cpu.r2, gpu.r2);
  same("prepare", "inten", pt, cpu.inten, gpu.inten);
  same("project", "point_pixel", pt, cpu.point_pixel, gpu.point_pixel);
  same("project", "pixel_key", px, cpu.pixel_key, gpu.pixel_key);
  same("project", "pixel_point", px, cpu.pixel_point, gpu.pixel_point);
  same("grid_reduce", "point_cell", pt, cpu.point_cell, gpu.point_cell);
  same("grid_reduce", "cell_zmin", cell, cpu.cell_zmin, gpu.cell_zmin);
  same("grid_reduce", "cell_zmax", cell, cpu.cell_zmax, gpu.cell_zmax);
  same("grid_reduce", "cell_count", cell, cpu.cell_count, gpu.cell_count);
  same("coarse_segment", "cell_seed_mode", cell, cpu.cell_seed_mode, gpu.cell_seed_mode);
  same("coarse_segment", "cell_plane", cell, cpu.cell_plane, gpu.cell_plane, 8);
  same("coarse_segment", "coarse", pt, cpu.coarse, gpu.coarse);
  same("feature_maps", "pixel_filled", px, cpu.pixel_filled, gpu.pixel_filled);
  same("feature_maps", "f_range", px, cpu.f_range, gpu.f_range);
  same("feature_maps", "f_inten", px, cpu.f_inten, gpu.f_inten);
  same("feature_maps", "f_height", px, cpu.f_height, gpu.f_height);
  same("feature_maps", "f_slope", px, cpu.f_slope, gpu.f_slope);
  same("feature_maps", "f_edge_l", px, cpu.f_edge_l, gpu.f_edge_l);
  same("feature_maps", "f_edge_r", px, cpu.f_edge_r, gpu.f_edge_r);
  same("feature_maps", "f_varz", px, cpu.f_varz, gpu.f_varz);
  same("feature_maps", "f_vari", px, cpu.f_vari, gpu.f_vari);
  same("classify_pixels", "pixel_class", px, cpu.pixel_class, gpu.pixel_class);
  same("fuse", "pixel_fused", px, cpu.pixel_fused, gpu.pixel_fused);
  same("grow", "pixel_grown", px, cpu.pixel_grown, gpu.pixel_grown);
  same("grow", "pixel_comp", px, cpu.pixel_comp, gpu.pixel_comp);
  same("grow", "pixel_label", px, cpu.pixel_label, gpu.pixel_label);
  same("back_project", "label", pt, cpu.label, gpu.label);
  same("back_project", "why", pt, cpu.why, gpu.why);
  same("back_project", "label_why", pt, cpu.label_why, gpu.label_why);
  return bytes;
}

}  // namespace lpir::test
