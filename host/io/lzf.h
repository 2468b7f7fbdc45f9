// LZF decompression (the format of Marc Lehmann's liblzf 3.x, which PCL's DATA binary_compressed
// PCD files hold), bounds-checked: a stream is a sequence of
//   literal run     control byte 000LLLLL, then L + 1 bytes copied as they are;
//   back reference  control byte NNNDDDDD (NNN > 0), [one more length byte E when NNN = 7], one
//                   distance byte D': copies NNN (+ E) + 2 bytes from 256 x DDDDD + D' + 1 bytes
//                   before the end of the output so far, byte by byte (it may overlap itself).
// Every read and write is checked against both buffers; nothing in the stream is trusted.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace lpir {

// The most bytes one byte of LZF can decode to: a 3-byte back reference copies at most
// 7 + 255 + 2 = 264 bytes. A claim of more than this times the compressed size is false.
constexpr size_t kLzfMaxExpansion = 88;

// Decodes the `in_size` bytes at `in` into exactly `out_size` bytes at `out`. IoError naming
// `path` and the byte offset in the stream for a run or reference cut short by the end of the
// stream, a reference to before the start of the output, output beyond `out_size`, or a stream
// that ends having written fewer than `out_size` bytes.
void LzfDecompress(const std::string& path, const uint8_t* in, size_t in_size, uint8_t* out,
                   size_t out_size);

}  // namespace lpir
