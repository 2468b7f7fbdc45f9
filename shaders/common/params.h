// Every threshold of the method, read by the shaders and the CPU reference alike: the struct of
// the rows of shaders/common/params.def, in their order (the stages' run order). Valid GLSL and
// C++: 32-bit scalars only, so that std140 (the shaders' uniform block) and C++ give every field
// the same offset; the C++ struct is aligned to 16 bytes as std140 rounds a struct's size. Units:
// metres, counts in pixels/points (the table's unit column). No parameter reads intensity: the
// method does not use it (docs/decisions/intensity.md).
#ifndef LPIR_SHADERS_COMMON_PARAMS_H_
#define LPIR_SHADERS_COMMON_PARAMS_H_

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace lpir {
using uint = uint32_t;
#define LPIR_PARAMS_ALIGN alignas(16)
#else
#define LPIR_PARAMS_ALIGN
#endif

struct LPIR_PARAMS_ALIGN Params {
#define LPIR_PARAM(stage, type, name, default_value, unit, swept, meaning) type name;
#define LPIR_DERIVED(stage, type, name, default_value, unit, meaning) type name;
#include "params.def"
};
#undef LPIR_PARAMS_ALIGN

#ifdef __cplusplus
// Each field's offset is its row's index times 4 (std140 places 32-bit scalars one after the
// other), and the size is the rows rounded up to whole vec4s (std140's size of a struct).
namespace params_layout {
enum Row : size_t {
#define LPIR_PARAM(stage, type, name, default_value, unit, swept, meaning) name,
#define LPIR_DERIVED(stage, type, name, default_value, unit, meaning) name,
#include "params.def"
  kRows
};
#define LPIR_PARAM(stage, type, name, default_value, unit, swept, meaning) \
  static_assert(sizeof(Params::name) == 4 && offsetof(Params, name) == 4 * name, #name);
#define LPIR_DERIVED(stage, type, name, default_value, unit, meaning) \
  static_assert(sizeof(Params::name) == 4 && offsetof(Params, name) == 4 * name, #name);
#include "params.def"
static_assert(sizeof(Params) == 16 * ((kRows + 3) / 4), "Params must be whole vec4s");
}  // namespace params_layout
}  // namespace lpir
#endif

#endif  // LPIR_SHADERS_COMMON_PARAMS_H_
