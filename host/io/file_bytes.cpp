#include "host/io/file_bytes.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "host/io/io_error.h"

namespace lpir {

void ReadFileInto(const std::string& path, const std::function<char*(size_t)>& room) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path, "no such file", ENOENT);
  if (std::filesystem::is_directory(path, ec))
    throw IoError(path, "is a folder, not a file", EISDIR);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw IoError(path, std::string("cannot open: ") + std::strerror(errno), errno);
  const std::streamoff size = in.tellg();
  if (size < 0) throw IoError(path, "cannot tell its size");
  char* data = room(static_cast<size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(data, size)) throw IoError(path, "read failed");
}

std::vector<char> ReadFileBytes(const std::string& path) {
  std::vector<char> bytes;
  ReadFileInto(path, [&](size_t size) {
    bytes.resize(size);
    return bytes.data();
  });
  return bytes;
}

void WriteFileBytes(const std::string& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError(path, std::string("cannot create: ") + std::strerror(errno), errno);
  out.write(static_cast<const char*>(data), std::streamsize(size));
  out.flush();
  if (!out) throw IoError(path, "write failed (disk full?)");
}

}  // namespace lpir
