// Linked into the tests of the ThreadSanitizer build only (LPIR_TSAN=ON): ThreadSanitizer's
// default options, so that ctest in build-tsan needs no more environment than the OpenMP tool
// (tests/CMakeLists.txt). LLVM's OpenMP runtime is not instrumented: its own memory accesses are
// ignored, and libarcher (OMP_TOOL_LIBRARIES) tells TSan of its barriers and forks, so that what
// is left are the project's accesses. TSAN_OPTIONS in the environment overrides this.
extern "C" const char* __tsan_default_options() { return "ignore_noninstrumented_modules=1"; }
