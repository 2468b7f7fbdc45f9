// The stages of the method (docs/spec.md, Stages), one file each: reference_cpu/<stage>.cpp,
// declared here from reference_cpu/stage_table.def. Each is a pure function of the cloud, the
// parameters, the host tables and earlier stages' buffers in the frame, and (re)writes only its own
// buffers. Their GPU twins are shaders/<stage>.comp. Each takes last the threads it may split its
// work over (reference_cpu/threads.h; by default one, the calling thread): the bytes are the same
// at any count.
#pragma once
#include "reference_cpu/cloud.h"
#include "reference_cpu/frame.h"
#include "reference_cpu/params.h"
#include "reference_cpu/threads.h"

namespace lpir {

// A table line's parameter list with the threads appended.
#define LPIR_WITH_THREADS(...) (__VA_ARGS__, Threads threads = Threads())
#define LPIR_STAGE(name, Type, parameters) void Type LPIR_WITH_THREADS parameters;
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
#undef LPIR_WITH_THREADS

// Exact geometric lookups shared by the stages and their tests.
uint32_t ColumnOf(float x, float y, const float* column_dir, uint32_t width);  // eq. 1, u
uint32_t RowOf(float z, float r2, const float* beam_bound, const float* beam_origin,
               uint32_t beams);                                       // eq. 1, v
uint32_t RingOf(float r2, const float* ring_bound2, uint32_t rings);  // eq. 4, i

}  // namespace lpir
