// The one error type of every reader and writer: the message always names the file.
#pragma once
#include <stdexcept>
#include <string>

namespace lpir {

class IoError : public std::runtime_error {
 public:
  // `error_number`: the errno behind the problem when the system refused (ENOENT for a missing
  // file, EISDIR for a folder where a file was expected), 0 when the file's contents are at fault.
  IoError(const std::string& path, const std::string& problem, int error_number = 0)
      : std::runtime_error(path + ": " + problem), error_number_(error_number) {}
  int error_number() const { return error_number_; }

 private:
  int error_number_;
};

}  // namespace lpir
