// The one error type of every reader and writer: the message always names the file.
#pragma once
#include <stdexcept>
#include <string>

namespace lpir {

class IoError : public std::runtime_error {
 public:
  IoError(const std::string& path, const std::string& problem)
      : std::runtime_error(path + ": " + problem) {}
};

}  // namespace lpir
