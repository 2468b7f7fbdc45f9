// Linked into every test executable and into lpir-gseg in the sanitizer build only
// (LPIR_SANITIZE=ON; the CLI tests run lpir-gseg, which loads the Vulkan driver too). It holds
// the sanitizers' default options, so that ctest in build-asan needs no environment, and keeps
// the Vulkan driver and validation layer loaded until exit. Why that is needed:
//  - The Vulkan loader dlclose()s the ICD (Mesa's lavapipe, libvulkan_lvp.so with libLLVM-15) and
//    the validation layer at vkDestroyInstance. LeakSanitizer runs at exit, after that: memory the
//    unloaded libraries still referenced from their globals is then reported as leaked, with stack
//    frames it can no longer name ("<unknown module>", or misattributed to libasan), so no
//    suppression by library can match. Opened here once more with RTLD_NODELETE (RTLD_LOCAL: no
//    symbol is interposed), they stay mapped: their globals are scanned and their frames named.
//  - What they then still leak is their own (measured: 7-320 KB per process, all in
//    libVkLayer_khronos_validation.so; lavapipe and LLVM leak nothing), suppressed by library in
//    tests/lsan_vulkan.supp: only third-party Vulkan libraries, never project code. A Vulkan object
//    the project forgets to destroy is still caught: the validation layer reports it at
//    vkDestroyDevice/vkDestroyInstance, which the VkTest fixture and the CLI tests fail on.
// LSAN_OPTIONS / ASAN_OPTIONS / UBSAN_OPTIONS set in the environment override these defaults.
#include <dlfcn.h>

#ifndef LPIR_LSAN_SUPPRESSIONS
#error "LPIR_LSAN_SUPPRESSIONS (the suppressions file's path) must be defined"
#endif

extern "C" {

const char* __asan_default_options() {
  // detect_leaks: on (the default on x86-64 Linux, stated). Stack use after return would double
  // the suite's time; initialisation order is checked.
  return "detect_leaks=1:check_initialization_order=1:strict_init_order=1";
}

const char* __lsan_default_options() { return "suppressions=" LPIR_LSAN_SUPPRESSIONS; }

const char* __ubsan_default_options() { return "print_stacktrace=1"; }

}  // extern "C"

namespace {

// The libraries as the loader opens them: the ICD by the absolute path of its manifest
// (/usr/share/vulkan/icd.d/lvp_icd.*.json), the layer by bare name
// (/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json). Missing ones are skipped.
__attribute__((constructor)) void PinVulkanLibraries() {
  const char* const kLibraries[] = {
      "libVkLayer_khronos_validation.so",
      "/usr/lib/x86_64-linux-gnu/libvulkan_lvp.so",
      "/usr/lib/aarch64-linux-gnu/libvulkan_lvp.so",
  };
  for (const char* library : kLibraries) dlopen(library, RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE);
}

}  // namespace
