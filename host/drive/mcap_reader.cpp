#include "host/drive/mcap_reader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <set>
#include <utility>

#include "host/drive/decompress.h"
#include "host/drive/mcap_records.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

using mcap::In;
using mcap::Malformed;

// The largest chunk this reader decompresses: a recorder's chunks are a few MiB; a claim past this
// is damage, not an allocation.
constexpr uint64_t kMaxChunkBytes = uint64_t(1) << 30;
// The summary's CRC is computed over the file in blocks of this size.
constexpr size_t kCrcBlock = size_t(1) << 20;

// A read-only file read by offset (pread): only the bytes asked for are ever in memory.
class File {
 public:
  explicit File(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw IoError(path, std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd_);
      throw IoError(path, "not a regular file");
    }
    size_ = uint64_t(st.st_size);
  }
  ~File() { ::close(fd_); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;

  uint64_t size() const { return size_; }
  // Bytes [offset, offset + n); the caller has checked that they lie inside the file.
  std::vector<uint8_t> Read(uint64_t offset, uint64_t n) const {
    std::vector<uint8_t> out(n);
    ReadInto(offset, out.data(), n);
    return out;
  }
  void ReadInto(uint64_t offset, uint8_t* out, uint64_t n) const {
    uint64_t done = 0;
    while (done < n) {
      const ssize_t r = ::pread(fd_, out + done, size_t(n - done), off_t(offset + done));
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) {
        throw IoError(
            path_, "cannot read " + std::to_string(n) + " bytes at byte " + std::to_string(offset) +
                       (r < 0 ? ": " + std::string(std::strerror(errno)) : ": the file shrank"));
      }
      done += uint64_t(r);
    }
  }

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

struct Channel {
  uint16_t schema_id = 0;
  std::string topic, encoding;
};

// Where a chunk lies (from its chunk index) and which channels it holds (empty: unknown).
struct ChunkRef {
  uint64_t start_time = 0, offset = 0, length = 0;
  std::set<uint16_t> channels;
};

// Receives each message record of a walk: channel, log time, data.
using Sink = std::function<void(uint16_t, uint64_t, const uint8_t*, size_t)>;

struct Pending {
  uint64_t log_time;
  std::vector<uint8_t> data;
};

// Open: the magic, the header, then the summary when the footer's is usable (ReadSummary). Next
// walks the chunk indexes in (message_start_time, offset) order when the summary has them, else
// the records from the header on (ScanStep); each chunk's messages of the chosen topic are
// queued in log-time order, then its damage, if any.
class McapReader : public DriveReader {
 public:
  explicit McapReader(const std::string& path) : path_(path), file_(path) {
    uint8_t magic[mcap::kMagicSize] = {};
    if (file_.size() < mcap::kMagicSize + mcap::kRecordPrefix) {
      throw IoError(path_, "not an MCAP file: " + std::to_string(file_.size()) +
                               " bytes, too short for the magic and a header record");
    }
    file_.ReadInto(0, magic, sizeof(magic));
    if (std::memcmp(magic, mcap::kMagic, sizeof(magic)) != 0) {
      throw IoError(path_, "not an MCAP file: the first 8 bytes are not the MCAP magic");
    }
    uint8_t op = 0;
    uint64_t length = 0;
    if (RecordAt(mcap::kMagicSize, &op, &length) != kWhole || op != mcap::kHeader) {
      throw IoError(path_, "no intact header record after the magic");
    }
    // Its two strings; a header past 1 MiB is read no further than that.
    const std::vector<uint8_t> header = file_.Read(mcap::kMagicSize + mcap::kRecordPrefix,
                                                   std::min<uint64_t>(length, uint64_t(1) << 20));
    try {
      In in(header.data(), header.size());
      profile_ = in.Str("header profile");
      in.Str("header library");
    } catch (const Malformed& e) {
      throw IoError(path_, std::string("header record: ") + e.what());
    }
    data_start_ = mcap::kMagicSize + mcap::kRecordPrefix + length;
    ReadSummary();
  }

  std::vector<DriveTopic> Topics() override {
    LoadTopics();
    std::vector<DriveTopic> topics;
    std::map<std::string, size_t> by_name;
    for (const auto& [id, ch] : channels_) {
      auto count = counts_.find(id);
      const uint64_t n = count == counts_.end() ? 0 : count->second;
      auto [it, fresh] = by_name.emplace(ch.topic, topics.size());
      if (!fresh) {
        topics[it->second].messages += n;
        continue;
      }
      DriveTopic t;
      t.name = ch.topic;
      auto schema = schemas_.find(ch.schema_id);
      if (schema != schemas_.end()) t.type = schema->second;
      t.encoding = ch.encoding;
      t.messages = n;
      topics.push_back(std::move(t));
    }
    return topics;
  }

  void SelectTopic(const std::string& topic) override {
    LoadTopics();
    std::set<uint16_t> selected;
    MessageEncoding encoding = MessageEncoding::kCdr;
    std::string names;
    for (const auto& [id, ch] : channels_) {
      if (ch.topic != topic) {
        names += (names.empty() ? "" : ", ") + ch.topic;
        continue;
      }
      if (ch.encoding == "cdr") {
        encoding = MessageEncoding::kCdr;
      } else if (ch.encoding == "ros1") {
        encoding = MessageEncoding::kRos1;
      } else {
        throw IoError(path_, "topic " + topic + " has message encoding '" + ch.encoding +
                                 "'; this reader reads cdr and ros1");
      }
      selected.insert(id);
    }
    if (selected.empty()) {
      throw IoError(path_, "no topic " + topic + " in the drive; it has: " +
                               (names.empty() ? std::string("none") : names));
    }
    selected_ = std::move(selected);
    encoding_ = encoding;
    topic_ = topic;
    pending_.clear();
    damage_.clear();
    done_ = false;
    next_chunk_ = 0;
    scan_ = Scan{data_start_, 0};
    sequence_ = 0;
  }

  DriveStep Next(DriveMessage* message, std::string* problem) override {
    if (selected_.empty()) throw IoError(path_, "Next before SelectTopic");
    for (;;) {
      if (!pending_.empty()) {
        message->sequence = sequence_++;
        message->log_time_ns = pending_.front().log_time;
        message->topic = topic_;
        message->encoding = encoding_;
        message->data = std::move(pending_.front().data);
        pending_.pop_front();
        return DriveStep::kMessage;
      }
      if (!damage_.empty()) {
        *problem = path_ + ": " + damage_ + " (after " + std::to_string(sequence_) +
                   (sequence_ == 1 ? " message" : " messages") + " of " + topic_ + ")";
        damage_.clear();
        return DriveStep::kDamage;
      }
      if (done_) return DriveStep::kEnd;
      Advance();
    }
  }

 private:
  enum RecordState { kWhole, kEndOfFile, kCutPrefix, kCutContent };
  struct Scan {
    uint64_t pos = 0;
    uint64_t chunks = 0;  // chunks met so far
  };

  // The record prefix at `pos`: whole, at the end of the file, or cut by it.
  RecordState RecordAt(uint64_t pos, uint8_t* op, uint64_t* length) const {
    if (pos == file_.size()) return kEndOfFile;
    if (file_.size() - pos < mcap::kRecordPrefix) return kCutPrefix;
    uint8_t prefix[mcap::kRecordPrefix];
    file_.ReadInto(pos, prefix, sizeof(prefix));
    In in(prefix, sizeof(prefix));
    *op = in.U8("opcode");
    *length = in.U64("length");
    return *length > file_.size() - pos - mcap::kRecordPrefix ? kCutContent : kWhole;
  }

  // The summary, used when the footer is intact, points at one and its CRC (when set) matches;
  // on any fault the summary is ignored and the file is scanned instead.
  void ReadSummary() {
    const uint64_t tail = mcap::kRecordPrefix + mcap::kFooterContent + mcap::kMagicSize;
    if (file_.size() < data_start_ + tail) return;
    const uint64_t footer_pos = file_.size() - tail;
    const std::vector<uint8_t> footer = file_.Read(footer_pos, tail);
    if (std::memcmp(footer.data() + tail - mcap::kMagicSize, mcap::kMagic, mcap::kMagicSize) != 0)
      return;
    In in(footer.data(), footer.size());
    if (in.U8("opcode") != mcap::kFooter || in.U64("length") != mcap::kFooterContent) return;
    const uint64_t summary_start = in.U64("summary_start");
    in.U64("summary_offset_start");
    const uint32_t summary_crc = in.U32("summary_crc");
    if (summary_start == 0 || summary_start < data_start_ || summary_start > footer_pos) return;
    if (summary_crc != 0) {
      uint32_t crc = 0;
      std::vector<uint8_t> block;
      const uint64_t end = footer_pos + mcap::kFooterCrcSpan;
      for (uint64_t at = summary_start; at < end; at += block.size()) {
        block = file_.Read(at, std::min<uint64_t>(kCrcBlock, end - at));
        crc = Crc32(block.data(), block.size(), crc);
      }
      if (crc != summary_crc) return;
    }
    std::map<uint16_t, std::string> schemas;
    std::map<uint16_t, Channel> channels;
    std::map<uint16_t, uint64_t> counts;
    std::vector<ChunkRef> chunks;
    bool have_counts = false;
    try {
      for (uint64_t pos = summary_start; pos < footer_pos;) {
        if (footer_pos - pos < mcap::kRecordPrefix) return;
        uint8_t op = 0;
        uint64_t length = 0;
        RecordAt(pos, &op, &length);
        if (length > footer_pos - pos - mcap::kRecordPrefix) return;
        const uint64_t content = pos + mcap::kRecordPrefix;
        pos = content + length;
        if (op != mcap::kSchema && op != mcap::kChannel && op != mcap::kChunkIndex &&
            op != mcap::kStatistics)
          continue;
        const std::vector<uint8_t> bytes = file_.Read(content, length);
        In r(bytes.data(), bytes.size());
        if (op == mcap::kSchema) {
          ParseSchema(&r, &schemas);
        } else if (op == mcap::kChannel) {
          ParseChannel(&r, &channels);
        } else if (op == mcap::kStatistics) {
          r.Take(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8, "statistics counts");
          const uint32_t n = r.U32("channel_message_counts length");
          In map(r.Take(n, "channel_message_counts"), n);
          while (map.left() > 0) {
            const uint16_t id = map.U16("channel id");
            counts[id] = map.U64("message count");
          }
          have_counts = !counts.empty() || channels.empty();
        } else {
          ChunkRef c;
          c.start_time = r.U64("message_start_time");
          r.U64("message_end_time");
          c.offset = r.U64("chunk_start_offset");
          c.length = r.U64("chunk_length");
          const uint32_t n = r.U32("message_index_offsets length");
          In map(r.Take(n, "message_index_offsets"), n);
          while (map.left() > 0) {
            c.channels.insert(map.U16("channel id"));
            map.U64("message index offset");
          }
          chunks.push_back(std::move(c));
        }
      }
    } catch (const Malformed&) {
      return;
    }
    std::stable_sort(chunks.begin(), chunks.end(), [](const ChunkRef& a, const ChunkRef& b) {
      return a.start_time != b.start_time ? a.start_time < b.start_time : a.offset < b.offset;
    });
    schemas_ = std::move(schemas);
    channels_ = std::move(channels);
    if (have_counts) {
      counts_ = std::move(counts);
      topics_loaded_ = true;
    }
    indexed_ = !chunks.empty();
    chunks_ = std::move(chunks);
  }

  void ParseSchema(In* r, std::map<uint16_t, std::string>* schemas) {
    const uint16_t id = r->U16("schema id");
    std::string name = r->Str("schema name");
    if (id != 0) schemas->emplace(id, std::move(name));  // id 0 is invalid: ignored
  }
  void ParseChannel(In* r, std::map<uint16_t, Channel>* channels) {
    const uint16_t id = r->U16("channel id");
    Channel c;
    c.schema_id = r->U16("channel schema_id");
    c.topic = r->Str("channel topic");
    c.encoding = r->Str("channel message_encoding");
    channels->emplace(id, std::move(c));
  }

  // Topics and counts by a scan of the whole file when the summary did not give them.
  void LoadTopics() {
    if (topics_loaded_) return;
    counts_.clear();
    Scan scan{data_start_, 0};
    std::string ignored;
    const Sink count = [this](uint16_t channel, uint64_t, const uint8_t*, size_t) {
      ++counts_[channel];
    };
    while (ScanStep(&scan, count, &ignored)) ignored.clear();
    topics_loaded_ = true;
  }

  // Fills pending_ / damage_ / done_ from the next chunk (indexed) or record (scanned).
  void Advance() {
    const Sink keep = [this](uint16_t channel, uint64_t time, const uint8_t* data, size_t size) {
      if (selected_.count(channel)) chunk_messages_.push_back({time, {data, data + size}});
    };
    chunk_messages_.clear();
    if (indexed_) {
      if (next_chunk_ == chunks_.size()) {
        done_ = true;
        return;
      }
      const ChunkRef& c = chunks_[next_chunk_++];
      bool wanted = c.channels.empty();
      for (uint16_t id : selected_) wanted = wanted || c.channels.count(id) > 0;
      if (wanted) ReadIndexedChunk(c, next_chunk_, keep);
    } else {
      done_ = !ScanStep(&scan_, keep, &damage_);
    }
    // Within a chunk, by log time; equal times keep their record order.
    std::stable_sort(chunk_messages_.begin(), chunk_messages_.end(),
                     [](const Pending& a, const Pending& b) { return a.log_time < b.log_time; });
    for (Pending& p : chunk_messages_) pending_.push_back(std::move(p));
    chunk_messages_.clear();
  }

  std::string Where(uint64_t chunk_number, uint64_t offset) const {
    return "chunk " + std::to_string(chunk_number) + " at byte " + std::to_string(offset);
  }

  void ReadIndexedChunk(const ChunkRef& c, uint64_t number, const Sink& sink) {
    const std::string where = Where(number, c.offset);
    if (c.offset < data_start_ || c.offset > file_.size() || c.length > file_.size() - c.offset ||
        c.length < mcap::kRecordPrefix) {
      damage_ = where + ": the chunk index points past the end of the file (" +
                std::to_string(c.length) + " bytes, the file has " + std::to_string(file_.size()) +
                ")";
      return;
    }
    uint8_t op = 0;
    uint64_t length = 0;
    RecordAt(c.offset, &op, &length);
    if (op != mcap::kChunk || length != c.length - mcap::kRecordPrefix) {
      damage_ = where + ": the chunk index does not point at a chunk record of its length";
      return;
    }
    const std::vector<uint8_t> bytes = file_.Read(c.offset + mcap::kRecordPrefix, length);
    damage_ = ReadChunk(where, bytes.data(), bytes.size(), false, sink);
  }

  // One step of a scan from scan->pos: handles one record and moves past it. Returns false when
  // the scan ends (data end, footer, end of file or a cut record); *damage is set when the step
  // met damage.
  bool ScanStep(Scan* scan, const Sink& sink, std::string* damage) {
    uint8_t op = 0;
    uint64_t length = 0;
    const uint64_t pos = scan->pos;
    const RecordState state = RecordAt(pos, &op, &length);
    if (state == kEndOfFile) {
      *damage = "the file ends at byte " + std::to_string(pos) +
                " without a data end or footer record (truncated)";
      return false;
    }
    if (state == kCutPrefix) {
      *damage =
          "byte " + std::to_string(pos) + ": the file ends inside a record prefix (truncated)";
      return false;
    }
    const uint64_t content = pos + mcap::kRecordPrefix;
    const uint64_t left = file_.size() - content;
    if (op == mcap::kChunk) {
      const uint64_t number = ++scan->chunks;
      const std::string where = Where(number, pos);
      if (state == kCutContent) {
        // The bytes there are, bounded by the chunk limit: an uncompressed chunk's complete
        // messages before the cut are still read.
        const std::vector<uint8_t> bytes =
            file_.Read(content, std::min<uint64_t>(left, kMaxChunkBytes + 4096));
        std::string problem = ReadChunk(where, bytes.data(), bytes.size(), true, sink);
        *damage = where + ": the file ends inside the chunk (" + std::to_string(length) +
                  " bytes, " + std::to_string(left) + " left; truncated)" +
                  (problem.empty() ? "" : "; " + problem.substr(where.size() + 2));
        return false;
      }
      const std::vector<uint8_t> bytes = file_.Read(content, length);
      *damage = ReadChunk(where, bytes.data(), bytes.size(), false, sink);
      scan->pos = content + length;
      return true;
    }
    if (state == kCutContent) {
      *damage = "byte " + std::to_string(pos) + ": the file ends inside a record of opcode " +
                std::to_string(op) + " (" + std::to_string(length) + " bytes, " +
                std::to_string(left) + " left; truncated)";
      return false;
    }
    scan->pos = content + length;
    if (op == mcap::kDataEnd || op == mcap::kFooter) return false;
    if (op != mcap::kSchema && op != mcap::kChannel && op != mcap::kMessage) return true;
    const std::vector<uint8_t> bytes = file_.Read(content, length);
    try {
      In r(bytes.data(), bytes.size());
      Record(op, &r, sink);
    } catch (const Malformed& e) {
      *damage = "byte " + std::to_string(pos) + ": malformed record of opcode " +
                std::to_string(op) + ": " + e.what();
    }
    return true;
  }

  // A schema, channel or message record (others are skipped).
  void Record(uint8_t op, In* r, const Sink& sink) {
    if (op == mcap::kSchema) {
      ParseSchema(r, &schemas_);
    } else if (op == mcap::kChannel) {
      ParseChannel(r, &channels_);
    } else if (op == mcap::kMessage) {
      const uint16_t channel = r->U16("message channel_id");
      r->U32("message sequence");
      const uint64_t log_time = r->U64("message log_time");
      r->U64("message publish_time");
      const size_t n = r->left();
      sink(channel, log_time, r->Take(n, "message data"), n);
    }
  }

  // A chunk record's content: checks, decompresses and walks its records, giving each message to
  // `sink`. `cut`: the content is the part of a chunk before the end of the file. Returns the
  // damage found ("" when none); the messages before a malformed record have been given.
  std::string ReadChunk(const std::string& where, const uint8_t* data, size_t size, bool cut,
                        const Sink& sink) {
    uint64_t uncompressed_size = 0, stored = 0;
    uint32_t crc = 0;
    std::string compression;
    const uint8_t* records = nullptr;
    try {
      In in(data, size);
      in.U64("message_start_time");
      in.U64("message_end_time");
      uncompressed_size = in.U64("uncompressed_size");
      crc = in.U32("uncompressed_crc");
      compression = in.Str("compression");
      stored = in.U64("records length");
      if (cut && stored > in.left()) {
        if (!compression.empty()) return where + ": its compressed records are cut";
        stored = in.left();
        uncompressed_size = stored;
        crc = 0;
      }
      records = in.Take(stored, "records");
    } catch (const Malformed& e) {
      return where + ": malformed chunk: " + e.what();
    }
    if (uncompressed_size > kMaxChunkBytes) {
      return where + ": the " + (compression.empty() ? std::string("uncompressed") : compression) +
             " chunk claims " + std::to_string(uncompressed_size) +
             " bytes uncompressed, more than the " + std::to_string(kMaxChunkBytes) +
             " this reader accepts";
    }
    std::vector<uint8_t> unpacked;
    const uint8_t* plain = records;
    size_t plain_size = size_t(stored);
    try {
      if (compression == "zstd") {
        unpacked = DecompressZstd(where, records, stored, size_t(uncompressed_size));
      } else if (compression == "lz4") {
        unpacked = DecompressLz4Frame(where, records, stored, size_t(uncompressed_size));
      } else if (!compression.empty()) {
        return where + ": unknown compression '" + compression + "'";
      } else if (stored != uncompressed_size) {
        return where + ": uncompressed records of " + std::to_string(stored) +
               " bytes, the chunk says " + std::to_string(uncompressed_size);
      }
    } catch (const IoError& e) {
      return std::string(e.what());  // "<where>: <library reason>"
    }
    if (!compression.empty()) {
      plain = unpacked.data();
      plain_size = unpacked.size();
    }
    if (crc != 0) {
      const uint32_t got = Crc32(plain, plain_size);
      if (got != crc) {
        char text[64];
        std::snprintf(text, sizeof(text), "CRC mismatch (records 0x%08x, the chunk says 0x%08x)",
                      got, crc);
        return where + ": " + text;
      }
    }
    size_t pos = 0;
    while (pos < plain_size) {
      if (plain_size - pos < mcap::kRecordPrefix) {
        return cut ? "" : where + ": a record prefix cut at chunk byte " + std::to_string(pos);
      }
      In prefix(plain + pos, mcap::kRecordPrefix);
      const uint8_t op = prefix.U8("opcode");
      const uint64_t length = prefix.U64("length");
      const size_t content = pos + mcap::kRecordPrefix;
      if (length > plain_size - content) {
        return cut ? ""
                   : where + ": a record of " + std::to_string(length) + " bytes at chunk byte " +
                         std::to_string(pos) + " overruns the chunk";
      }
      try {
        In r(plain + content, size_t(length));
        Record(op, &r, sink);
      } catch (const Malformed& e) {
        return where + ": malformed record of opcode " + std::to_string(op) + " at chunk byte " +
               std::to_string(pos) + ": " + e.what();
      }
      pos = content + size_t(length);
    }
    return "";
  }

  const std::string path_;
  File file_;
  std::string profile_;
  uint64_t data_start_ = 0;  // the first byte after the header record

  std::map<uint16_t, std::string> schemas_;  // id -> name
  std::map<uint16_t, Channel> channels_;
  std::map<uint16_t, uint64_t> counts_;
  bool topics_loaded_ = false;
  bool indexed_ = false;  // chunks_ (from the summary) drive Next
  std::vector<ChunkRef> chunks_;

  // The walk of the selected topic.
  std::set<uint16_t> selected_;
  std::string topic_;
  MessageEncoding encoding_ = MessageEncoding::kCdr;
  uint64_t sequence_ = 0;
  size_t next_chunk_ = 0;
  Scan scan_;
  std::vector<Pending> chunk_messages_;
  std::deque<Pending> pending_;
  std::string damage_;
  bool done_ = false;
};

}  // namespace

std::unique_ptr<DriveReader> OpenMcap(const std::string& path) {
  return std::make_unique<McapReader>(path);
}

}  // namespace lpir
