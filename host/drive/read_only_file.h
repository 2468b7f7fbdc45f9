// A drive file read by offset (pread): the readers hold only the bytes they ask for, and several
// threads may read one file at once (host/drive/chunk_pool.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lpir {

class ReadOnlyFile {
 public:
  // IoError naming `path`: no such file, a folder, cannot be opened (the OS's reason), not a
  // regular file.
  explicit ReadOnlyFile(const std::string& path);
  ~ReadOnlyFile();
  ReadOnlyFile(const ReadOnlyFile&) = delete;
  ReadOnlyFile& operator=(const ReadOnlyFile&) = delete;

  uint64_t size() const { return size_; }
  // Bytes [offset, offset + n) into `out`; the caller has checked that they lie inside the file.
  // IoError naming the file, the count and the offset when the OS fails the read or the file has
  // shrunk since it was opened.
  void ReadInto(uint64_t offset, uint8_t* out, uint64_t n) const;
  // The same bytes as a vector.
  std::vector<uint8_t> Bytes(uint64_t offset, uint64_t n) const;

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

}  // namespace lpir
