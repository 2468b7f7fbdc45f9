// Fuzz target of the SemanticKITTI .label reader (host/io/label_file.h): a whole number of
// uint32 reads as exactly those values, with or without the expected count; a wrong expected
// count, an empty file or a ragged size throws IoError. Anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz/fuzz_file.h"
#include "host/io/io_error.h"
#include "host/io/label_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lpir;
  static fuzz::FuzzFile in;
  in.Write(data, size);
  const bool whole = size > 0 && size % 4 == 0;
  std::vector<uint32_t> labels;
  try {
    labels = ReadLabelFile(in.path());
  } catch (const IoError&) {
    LPIR_FUZZ_CHECK(!whole);
    return 0;
  }
  LPIR_FUZZ_CHECK(whole);
  LPIR_FUZZ_CHECK(labels.size() == size / 4);
  LPIR_FUZZ_CHECK(std::memcmp(labels.data(), data, size) == 0);
  LPIR_FUZZ_CHECK(ReadLabelFile(in.path(), labels.size()) == labels);
  std::string message;  // of the read that expects one label too many
  try {
    ReadLabelFile(in.path(), labels.size() + 1);
  } catch (const IoError& e) {
    message = e.what();
  }
  LPIR_FUZZ_CHECK(message.find(in.path()) != std::string::npos);
  LPIR_FUZZ_CHECK(message.find(std::to_string(labels.size() + 1)) != std::string::npos);
  return 0;
}
