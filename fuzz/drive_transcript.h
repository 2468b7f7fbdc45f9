// What a drive reader yields, as text, so that two readers of one file can be compared: for each
// of the first `max_topics` topics of Topics(), in order, the topic's name, then one line per step
// of Next until kEnd or `max_steps` steps (a message: sequence, log time and a hash of its bytes;
// a damage: the problem), or "unreadable" where SelectTopic throws IoError. The fuzz targets
// read each input with one worker and with several (host/drive/chunk_pool.h) and require equal
// transcripts: the workers may change when a chunk is decompressed, never what is yielded.
// TranscriptOf opens the reader itself: an IoError from the open, Topics() or a step ends the
// transcript with "error" and its text.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "host/drive/drive.h"
#include "host/io/io_error.h"

namespace lpir::fuzz {

inline uint64_t Fnv1a(const std::vector<uint8_t>& bytes) {
  uint64_t h = 14695981039346656037ull;
  for (uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return h;
}

inline std::string DriveTranscript(DriveReader& reader, size_t max_topics, size_t max_steps) {
  std::string out;
  const std::vector<DriveTopic> topics = reader.Topics();
  for (size_t t = 0; t < topics.size() && t < max_topics; ++t) {
    out += topics[t].name + "\n";
    try {
      reader.SelectTopic(topics[t].name);
    } catch (const IoError&) {
      out += "unreadable\n";
      continue;
    }
    DriveMessage message;
    std::string problem;
    for (size_t step = 0; step < max_steps; ++step) {
      const DriveStep s = reader.Next(&message, &problem);
      if (s == DriveStep::kEnd) break;
      if (s == DriveStep::kDamage) {
        out += "damage " + problem + "\n";
      } else {
        out += "message " + std::to_string(message.sequence) + " " +
               std::to_string(message.log_time_ns) + " " + std::to_string(Fnv1a(message.data)) +
               "\n";
      }
    }
  }
  return out;
}

// open(threads) returns the reader (a std::unique_ptr<DriveReader>).
template <typename Open>
std::string TranscriptOf(Open open, unsigned threads, size_t max_topics, size_t max_steps) {
  try {
    auto reader = open(threads);
    return DriveTranscript(*reader, max_topics, max_steps);
  } catch (const IoError& e) {
    return std::string("error ") + e.what();
  }
}

}  // namespace lpir::fuzz
