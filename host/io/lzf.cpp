// LZF decompression (see lzf.h): the reading order of liblzf's lzf_decompress, every length
// checked before it is used.
#include "host/io/lzf.h"

#include <cstring>

#include "host/io/io_error.h"

namespace lpir {

void LzfDecompress(const std::string& path, const uint8_t* in, size_t in_size, uint8_t* out,
                   size_t out_size) {
  const auto fail = [&](size_t at, const std::string& problem) {
    throw IoError(path, "LZF data, byte " + std::to_string(at) + " of " + std::to_string(in_size) +
                            ": " + problem);
  };
  const auto overflow = [&](size_t at, size_t op, size_t length) {
    fail(at, "copies " + std::to_string(length) + " bytes at output byte " + std::to_string(op) +
                 ", past the " + std::to_string(out_size) + " bytes the data should decode to");
  };
  size_t ip = 0, op = 0;
  while (ip < in_size) {
    const size_t at = ip;
    const unsigned control = in[ip++];
    if (control < 32) {  // a literal run of control + 1 bytes
      const size_t length = control + 1;
      if (length > in_size - ip) {
        fail(at, "a run of " + std::to_string(length) + " bytes cut short by the end of the data");
      }
      if (length > out_size - op) overflow(at, op, length);
      std::memcpy(out + op, in + ip, length);
      ip += length;
      op += length;
      continue;
    }
    size_t length = control >> 5;  // then + 2
    if (length == 7) {
      if (ip == in_size) fail(at, "a reference cut short by the end of the data");
      length += in[ip++];
    }
    if (ip == in_size) fail(at, "a reference cut short by the end of the data");
    const size_t distance = ((size_t(control & 0x1f) << 8) | in[ip++]) + 1;
    length += 2;
    if (distance > op) {
      fail(at, "a reference " + std::to_string(distance) + " bytes back from output byte " +
                   std::to_string(op) + ", before the start of the output");
    }
    if (length > out_size - op) overflow(at, op, length);
    const uint8_t* from = out + op - distance;
    if (distance >= length) {
      std::memcpy(out + op, from, length);
    } else {  // the copy reads bytes it writes: a repeated pattern
      for (size_t k = 0; k < length; ++k) out[op + k] = from[k];
    }
    op += length;
  }
  if (op != out_size) {
    throw IoError(path, "LZF data decodes to " + std::to_string(op) + " bytes, not the " +
                            std::to_string(out_size) + " it should");
  }
}

}  // namespace lpir
