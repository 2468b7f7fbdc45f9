// Fuzz target of the ROS 2 .db3 reader (host/drive/db3_reader.h): any bytes as a bag either
// throw IoError from OpenDb3, Topics or SelectTopic, or read as a stream of messages numbered
// from 0 that ends (kEnd, right after a kDamage when there is one); each message's bytes go
// through the PointCloud2 decoder too; its whole-drive reader (OpenDb3Content) keeps the
// DriveContent contract (fuzz/content_walk.h). A crash, a hang, another exception or a failed
// check is a finding. The bytes go to a real temporary file, not FuzzFile's memfd: SQLite resolves
// the /proc/self/fd/N link to the memfd's name, which it cannot open.
#include <fcntl.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz/cloud_checks.h"
#include "fuzz/content_walk.h"
#include "fuzz/fuzz_file.h"
#include "host/drive/db3_reader.h"
#include "host/drive/pointcloud2.h"
#include "host/io/io_error.h"

namespace {

// A file under $TMPDIR (else /tmp) whose bytes are replaced per input; removed at exit.
class DiskFile {
 public:
  DiskFile() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/lpir_db3_fuzz_XXXXXX";
    fd_ = mkstemp(pattern.data());
    LPIR_FUZZ_CHECK(fd_ >= 0);
    path_ = pattern;
  }
  ~DiskFile() {
    close(fd_);
    unlink(path_.c_str());
  }
  DiskFile(const DiskFile&) = delete;
  DiskFile& operator=(const DiskFile&) = delete;
  void Write(const uint8_t* data, size_t size) {
    LPIR_FUZZ_CHECK(ftruncate(fd_, 0) == 0);
    size_t done = 0;
    while (done < size) {
      const ssize_t n = pwrite(fd_, data + done, size - done, off_t(done));
      LPIR_FUZZ_CHECK(n > 0);
      done += size_t(n);
    }
  }
  const std::string& path() const { return path_; }

 private:
  int fd_ = -1;
  std::string path_;
};

// Reads every message of `topic`; the file holds at most a few thousand rows, so the loop is
// bounded by far more than any input can hold.
void ReadTopic(lpir::DriveReader* reader, const std::string& path, const std::string& topic) {
  using namespace lpir;
  try {
    reader->SelectTopic(topic);
  } catch (const IoError&) {
    return;
  }
  uint64_t sequence = 0;
  for (int call = 0; call < 100000; ++call) {
    DriveMessage message;
    std::string problem;
    const DriveStep step = reader->Next(&message, &problem);
    if (step == DriveStep::kEnd) return;
    if (step == DriveStep::kDamage) {
      LPIR_FUZZ_CHECK(problem.find(path) != std::string::npos);
      LPIR_FUZZ_CHECK(reader->Next(&message, &problem) == DriveStep::kEnd);
      return;
    }
    LPIR_FUZZ_CHECK(message.sequence == sequence++);
    LPIR_FUZZ_CHECK(message.topic == topic);
    LPIR_FUZZ_CHECK(message.encoding == MessageEncoding::kCdr);
    try {
      const PointCloud2 msg = ParseCdrPointCloud2(path, message.data.data(), message.data.size());
      fuzz::CheckCloudShape(CloudFromPointCloud2(path, msg));
    } catch (const IoError&) {
    }
  }
  LPIR_FUZZ_CHECK(false);  // never ended
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace lpir;
  static DiskFile file;
  file.Write(data, size);
  std::unique_ptr<DriveReader> reader;
  try {
    reader = OpenDb3(file.path());
  } catch (const IoError& e) {
    LPIR_FUZZ_CHECK(std::string(e.what()).find(file.path()) != std::string::npos);
    return 0;
  }
  std::vector<std::string> names = {"/points"};
  try {
    names.clear();
    for (const DriveTopic& topic : reader->Topics()) {
      if (names.size() < 4) names.push_back(topic.name);
    }
  } catch (const IoError&) {
    names = {"/points"};  // the counts are damaged; the messages may still be read
  }
  for (const std::string& name : names) ReadTopic(reader.get(), file.path(), name);
  fuzz::CheckContentWalk(OpenDb3Content, file.path());
  return 0;
}
