// Fuzz target of the MCAP reader (host/drive/mcap_reader.h): any bytes either throw IoError (at
// open, Topics or SelectTopic) or give a reader whose walk of every topic keeps the DriveReader
// contract: it ends (kEnd within a bound, and stays ended), sequences count 0, 1, 2, ..., every
// message carries the topic chosen, every damage names the file. Any other exception, a sanitizer
// report, a leak or a failed check is a finding. Read again with one worker and with three
// decompressing ahead, the file yields the same steps (fuzz/drive_transcript.h). Its whole-drive
// reader (OpenMcapContent) keeps the DriveContent contract (fuzz/content_walk.h).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/content_walk.h"
#include "fuzz/drive_transcript.h"
#include "fuzz/fuzz_file.h"
#include "host/drive/mcap_reader.h"
#include "host/io/io_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static lpir::fuzz::FuzzFile in;
  in.Write(data, size);
  try {
    auto reader = lpir::OpenMcap(in.path());
    const std::vector<lpir::DriveTopic> topics = reader->Topics();
    for (size_t t = 0; t < topics.size() && t < 4; ++t) {
      try {
        reader->SelectTopic(topics[t].name);
      } catch (const lpir::IoError&) {
        continue;  // an encoding the reader does not read
      }
      lpir::DriveMessage message;
      std::string problem;
      uint64_t messages = 0;
      bool ended = false;
      // Every step consumes a record or ends; chunks may decompress (and chunk indexes repeat)
      // to many messages, so the bound is loose: a reader that loops forever fails it.
      for (size_t step = 0; step < (size_t(1) << 26); ++step) {
        const lpir::DriveStep s = reader->Next(&message, &problem);
        if (s == lpir::DriveStep::kEnd) {
          ended = true;
          break;
        }
        if (s == lpir::DriveStep::kMessage) {
          LPIR_FUZZ_CHECK(message.sequence == messages);
          LPIR_FUZZ_CHECK(message.topic == topics[t].name);
          ++messages;
        } else {
          LPIR_FUZZ_CHECK(problem.rfind(in.path(), 0) == 0);
        }
      }
      LPIR_FUZZ_CHECK(ended);
      LPIR_FUZZ_CHECK(reader->Next(&message, &problem) == lpir::DriveStep::kEnd);
    }
  } catch (const lpir::IoError&) {
  }
  // The same file read with three workers decompressing ahead yields the same steps.
  const auto open = [&](unsigned threads) { return lpir::OpenMcap(in.path(), threads); };
  LPIR_FUZZ_CHECK(lpir::fuzz::TranscriptOf(open, 1, 4, size_t(1) << 20) ==
                  lpir::fuzz::TranscriptOf(open, 3, 4, size_t(1) << 20));
  lpir::fuzz::CheckContentWalk(lpir::OpenMcapContent, in.path());
  return 0;
}
