// lpir-gseg's WriteImages and LoadImages (apps/viz/images.h): the pictures' library,
// liblpir_images.so, loaded from the program's folder on the first call, then its
// lpir_write_images called. Not linked to the program, so that OpenCV and the libraries it needs
// are loaded only by a run that draws pictures.
#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/viz/images.h"

namespace lpir {
namespace {

using WriteImagesFn = void (*)(const std::string&, const std::string&, const Cloud&, const Frame&,
                               const Params&, const std::vector<uint8_t>*,
                               std::vector<std::string>*);

// The library's WriteImages: loaded once (never unloaded); a failure throws and the next call
// tries again.
WriteImagesFn Loaded() {
  static const WriteImagesFn write = [] {
    std::error_code ec;
    const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string library = (program.parent_path() / "liblpir_images.so").string();
    void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
      throw std::runtime_error(library + ": cannot load the pictures' library (built beside " +
                               "lpir-gseg with it): " + dlerror());
    void* entry = dlsym(handle, "lpir_write_images");
    if (!entry)
      throw std::runtime_error(library + ": not the pictures' library: no lpir_write_images");
    return reinterpret_cast<WriteImagesFn>(entry);
  }();
  return write;
}

}  // namespace

void LoadImages() { Loaded(); }

std::vector<std::string> WriteImages(const std::string& dir, const std::string& stem,
                                     const Cloud& cloud, const Frame& frame, const Params& params,
                                     const std::vector<uint8_t>* truth) {
  std::vector<std::string> written;
  Loaded()(dir, stem, cloud, frame, params, truth, &written);
  return written;
}

}  // namespace lpir
