// Fuzz target of the ROS 1 bag reader (host/drive/ros1_bag_reader.h) and the ROS 1 PointCloud2
// parser: any bytes either fail to open with IoError, or list their topics without throwing and
// yield, for each topic (the first 8), a finite run of steps ending in kEnd (and kEnd again) in
// which the messages are numbered 0, 1, ... in receipt-time order, carry the topic, number the
// topic's count from Topics() when no damage was reported, and every damage names the file. A
// message that parses as a PointCloud2 serializes back to the same bytes. Any other exception,
// a sanitizer report, a leak or a failed check is a finding. Read again with one worker and with
// three decompressing ahead, the file yields the same steps (fuzz/drive_transcript.h). Its
// whole-drive reader (OpenRos1BagContent) keeps the DriveContent contract (fuzz/content_walk.h).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fuzz/content_walk.h"
#include "fuzz/drive_transcript.h"
#include "fuzz/fuzz_file.h"
#include "host/drive/pointcloud2.h"
#include "host/drive/ros1_bag_reader.h"
#include "host/io/io_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static lpir::fuzz::FuzzFile file;
  file.Write(data, size);
  std::unique_ptr<lpir::DriveReader> reader;
  try {
    reader = lpir::OpenRos1Bag(file.path());
  } catch (const lpir::IoError&) {
    return 0;
  }
  const std::vector<lpir::DriveTopic> topics = reader->Topics();
  for (size_t t = 0; t < topics.size() && t < 8; ++t) {
    reader->SelectTopic(topics[t].name);
    uint64_t messages = 0, damages = 0, last_time = 0;
    lpir::DriveMessage message;
    std::string problem;
    for (;;) {
      const lpir::DriveStep step = reader->Next(&message, &problem);
      if (step == lpir::DriveStep::kEnd) break;
      if (step == lpir::DriveStep::kDamage) {
        LPIR_FUZZ_CHECK(problem.find(file.path()) != std::string::npos);
        ++damages;
      } else {
        LPIR_FUZZ_CHECK(message.sequence == messages);
        LPIR_FUZZ_CHECK(message.topic == topics[t].name);
        LPIR_FUZZ_CHECK(message.encoding == lpir::MessageEncoding::kRos1);
        LPIR_FUZZ_CHECK(messages == 0 || message.log_time_ns >= last_time);
        last_time = message.log_time_ns;
        ++messages;
        try {
          const lpir::PointCloud2 cloud =
              lpir::ParseRos1PointCloud2("message", message.data.data(), message.data.size());
          LPIR_FUZZ_CHECK(lpir::SerializeRos1PointCloud2(cloud) == message.data);
        } catch (const lpir::IoError&) {
        }
      }
      // A message or a damage costs bytes of the file: more steps than bytes is a loop.
      LPIR_FUZZ_CHECK(messages + damages <= size);
    }
    LPIR_FUZZ_CHECK(reader->Next(&message, &problem) == lpir::DriveStep::kEnd);
    LPIR_FUZZ_CHECK(damages > 0 || messages == topics[t].messages);
  }
  // The same file read with three workers decompressing ahead yields the same steps.
  const auto open = [&](unsigned threads) { return lpir::OpenRos1Bag(file.path(), threads); };
  LPIR_FUZZ_CHECK(lpir::fuzz::TranscriptOf(open, 1, 8, size_t(1) << 20) ==
                  lpir::fuzz::TranscriptOf(open, 3, 8, size_t(1) << 20));
  lpir::fuzz::CheckContentWalk(lpir::OpenRos1BagContent, file.path());
  return 0;
}
