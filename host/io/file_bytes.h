// Whole-file reads and writes with errors that name the file.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace lpir {

// The file's bytes; IoError when it is missing, a folder, or unreadable.
std::vector<char> ReadFileBytes(const std::string& path);
// The file's bytes read into the room that room(size) returns, size being the file's size (room
// for size bytes; not read when size is 0), so that a caller's own buffer takes them without a
// copy; the errors of ReadFileBytes, and whatever room throws (before anything is read).
void ReadFileInto(const std::string& path, const std::function<char*(size_t)>& room);
// Writes (replacing) the file; IoError when it cannot be written completely.
void WriteFileBytes(const std::string& path, const void* data, size_t size);

}  // namespace lpir
