// Whole-file reads and writes with errors that name the file.
#pragma once
#include <string>
#include <vector>

namespace lpir {

// The file's bytes; IoError when it is missing, a folder, or unreadable.
std::vector<char> ReadFileBytes(const std::string& path);
// Writes (replacing) the file; IoError when it cannot be written completely.
void WriteFileBytes(const std::string& path, const void* data, size_t size);

}  // namespace lpir
