// The codes the frame's buffers hold, read by the shaders and the CPU reference alike (valid GLSL
// and C++, as params.h): the "nothing" index, point flags, pixel classes and why a point got its
// label. reference_cpu/frame.h includes it; a shader includes it after common/params.h. Each code
// is LPIR_CODE(C++ type, name, value): constexpr of that type in C++, a uint constant in GLSL.
#ifndef LPIR_SHADERS_COMMON_FRAME_CODES_H_
#define LPIR_SHADERS_COMMON_FRAME_CODES_H_

#ifdef __cplusplus
#include <cstdint>
namespace lpir {
#define LPIR_CODE(type, name, value) constexpr type name = value;
#else
#define LPIR_CODE(type, name, value) const uint name = value;
#endif

LPIR_CODE(uint32_t, kNone, 0xFFFFFFFFu)  // "no point" / "no pixel"

// Point flags (prepare).
LPIR_CODE(uint32_t, kPointValid, 1u)  // finite, not at the origin, inside the range limits
LPIR_CODE(uint32_t, kPointNoise, 2u)  // reflection noise (III-B.1), valid but never ground

// Pixel classes (classify_pixels, fuse, grow).
LPIR_CODE(uint32_t, kPixNonGround, 0u)
LPIR_CODE(uint32_t, kPixGround, 1u)
LPIR_CODE(uint32_t, kPixUnknown, 2u)
LPIR_CODE(uint32_t, kPixEmpty, 3u)
// pixel_fused and pixel_grown only: a pixel the occlusion veto (fuse) took from ground or unknown;
// in pixel_label grow makes it ground where it lifts the veto, else non-ground.
LPIR_CODE(uint32_t, kPixVetoed, 4u)
// pixel_class only: non-ground by eq. 12, but a smooth slope (f_slope < bank_slope, f_varz <
// bank_rough): a bank, which fuse leaves unknown where the coarse label is non-ground.
LPIR_CODE(uint32_t, kPixBank, 5u)
// pixel_fused only: unknown where the coarse segmentation saw no ground (its label of the pixel's
// point non-ground, or no point: a filled hole); grow may climb to it up a bank's grade.
LPIR_CODE(uint32_t, kPixUnknownOff, 6u)

// Why a point got its final label (back_project; for tools and pictures).
LPIR_CODE(uint8_t, kWhyNonGround, 0u)
LPIR_CODE(uint8_t, kWhyGround, 1u)
LPIR_CODE(uint8_t, kWhyInvalid, 2u)
LPIR_CODE(uint8_t, kWhyNoise, 3u)

#undef LPIR_CODE
#ifdef __cplusplus
}  // namespace lpir
#endif

#endif  // LPIR_SHADERS_COMMON_FRAME_CODES_H_
