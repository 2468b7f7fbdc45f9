#include "host/drive/read_only_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "host/io/io_error.h"

namespace lpir {

ReadOnlyFile::ReadOnlyFile(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path, "no such file", ENOENT);
  if (std::filesystem::is_directory(path, ec))
    throw IoError(path, "is a folder, not a file", EISDIR);
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw IoError(path, std::string("cannot open: ") + std::strerror(errno), errno);
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw IoError(path, "not a regular file");
  }
  size_ = uint64_t(st.st_size);
}

ReadOnlyFile::~ReadOnlyFile() { ::close(fd_); }

void ReadOnlyFile::ReadInto(uint64_t offset, uint8_t* out, uint64_t n) const {
  uint64_t done = 0;
  while (done < n) {
    const ssize_t r = ::pread(fd_, out + done, size_t(n - done), off_t(offset + done));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) {
      throw IoError(
          path_, "cannot read " + std::to_string(n) + " bytes at byte " + std::to_string(offset) +
                     (r < 0 ? ": " + std::string(std::strerror(errno)) : ": the file shrank"));
    }
    done += uint64_t(r);
  }
}

std::vector<uint8_t> ReadOnlyFile::Bytes(uint64_t offset, uint64_t n) const {
  std::vector<uint8_t> out(n);
  ReadInto(offset, out.data(), n);
  return out;
}

}  // namespace lpir
