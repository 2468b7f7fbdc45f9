// Stages 1-9 of the method (SPEC section 2), one file each: reference_cpu/<stage>.cpp. Each is a
// pure function of the cloud, the parameters, the host tables and earlier stages' buffers in
// `frame`, and (re)writes only its own buffers. Their GPU twins are shaders/<stage>.comp.
#pragma once
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"

namespace lpir {

void Prepare(const Cloud& cloud, const Params& p, Frame& f);                         // 1
void Project(const Cloud& cloud, const Params& p, const Tables& t, Frame& f);        // 2
void GridReduce(const Params& p, const Tables& t, Frame& f);                         // 3
void CoarseSegment(const Cloud& cloud, const Params& p, const Tables& t, Frame& f);  // 4
void FeatureMaps(const Params& p, Frame& f);                                         // 5
void ClassifyPixels(const Params& p, Frame& f);                                      // 6
void Fuse(const Params& p, Frame& f);                                                // 7
void Grow(const Params& p, Frame& f);                                                // 8
void BackProject(const Params& p, Frame& f);                                         // 9

// Exact geometric lookups shared by the stages and their tests.
uint32_t ColumnOf(float x, float y, const float* column_dir, uint32_t width);  // eq. 1, u
uint32_t RowOf(float z, float r2, const float* beam_bound, const float* beam_origin,
               uint32_t beams);                                       // eq. 1, v
uint32_t RingOf(float r2, const float* ring_bound2, uint32_t rings);  // eq. 4, i

}  // namespace lpir
