// The DriveContent contract (host/drive/drive_content.h) checked on any file, for the drive fuzz
// targets: the whole-drive reader opens or throws IoError; its walk ends (kEnd within a bound,
// and kEnd again); a schema or channel id is yielded once; every message names a channel
// yielded before it; every damage names the file. Any other exception is a finding.
#pragma once
#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <variant>

#include "fuzz/fuzz_file.h"
#include "host/drive/drive_content.h"
#include "host/io/io_error.h"

namespace lpir::fuzz {

inline void CheckContentWalk(std::unique_ptr<DriveContent> (*open)(const std::string&),
                             const std::string& path) {
  std::unique_ptr<DriveContent> content;
  try {
    content = open(path);
  } catch (const IoError&) {
    return;
  }
  std::set<uint16_t> schemas, channels;
  DriveRecord record;
  std::string problem;
  bool ended = false;
  // Every step consumes a record or ends; chunks may decompress to many records.
  for (size_t step = 0; step < (size_t(1) << 24) && !ended; ++step) {
    switch (content->Next(&record, &problem)) {
      case ContentStep::kEnd:
        ended = true;
        break;
      case ContentStep::kDamage:
        LPIR_FUZZ_CHECK(problem.rfind(path, 0) == 0);
        break;
      case ContentStep::kRecord:
        if (const auto* s = std::get_if<DriveSchema>(&record)) {
          LPIR_FUZZ_CHECK(s->id != 0 && schemas.insert(s->id).second);
        } else if (const auto* c = std::get_if<DriveChannel>(&record)) {
          LPIR_FUZZ_CHECK(channels.insert(c->id).second);
        } else if (const auto* m = std::get_if<DriveRecordMessage>(&record)) {
          LPIR_FUZZ_CHECK(channels.count(m->channel_id) == 1);
        }
        break;
    }
  }
  LPIR_FUZZ_CHECK(ended);
  LPIR_FUZZ_CHECK(content->Next(&record, &problem) == ContentStep::kEnd);
}

}  // namespace lpir::fuzz
