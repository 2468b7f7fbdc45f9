#include "host/drive/mcap_reader.h"

#include <algorithm>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include "host/drive/chunk_pool.h"
#include "host/drive/decompress.h"
#include "host/drive/mcap_file.h"
#include "host/drive/mcap_records.h"
#include "host/drive/read_only_file.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

using mcap::In;
using mcap::kCutContent;
using mcap::kCutPrefix;
using mcap::kEndOfFile;
using mcap::kWhole;
using mcap::Malformed;
using mcap::RecordState;
using mcap::Scan;

// The summary's CRC is computed over the file in blocks of this size.
constexpr size_t kCrcBlock = size_t(1) << 20;

struct Channel {
  uint16_t schema_id = 0;
  std::string topic, encoding;
};

// Where a chunk lies (from its chunk index) and which channels it holds (empty: unknown), with
// the offset of each one's message index record.
struct ChunkRef {
  uint64_t start_time = 0, offset = 0, length = 0;
  std::set<uint16_t> channels;
  std::map<uint16_t, uint64_t> message_indexes;  // channel -> message index record's offset
};

// Where schema and channel records found by a walk go.
struct Defs {
  std::map<uint16_t, std::string>* schemas;  // id -> name
  std::map<uint16_t, Channel>* channels;
};

// Receives each message record of a walk: channel, log time, data.
using Sink = std::function<void(uint16_t, uint64_t, const uint8_t*, size_t)>;

struct Pending {
  uint64_t log_time;
  std::vector<uint8_t> data;
};

// One step of the walk of the selected topic: a chunk from the chunk indexes, or a record of the
// scan (a chunk, schema, channel or message record, or where the scan ends).
struct Step {
  uint64_t pos = 0;            // scan: the record's byte
  uint64_t chunks_before = 0;  // scan: the chunk records before it
  size_t chunk = 0;            // indexed: its place in chunks_ (its number - 1)
  uint64_t owner = 0;          // the number of the chunk it is or follows (0: before every chunk)
  bool is_chunk = false;
};

// What a step gave: the selected topic's messages in log-time order (equal times in record
// order), its damage ("" when none), the schemas and channels it defined.
struct StepResult {
  std::vector<Pending> messages;
  std::string damage;
  std::map<uint16_t, std::string> schemas;
  std::map<uint16_t, Channel> channels;
};

// Open: the magic, the header, then the summary when the footer's is usable (ReadSummary). Next
// walks the chunk indexes in (message_start_time, offset) order when the summary has them, else
// the records from the header on (the steps ListScan finds, each read as ScanStep reads it);
// each chunk's messages of the chosen topic are queued in log-time order, then its damage, if
// any. The steps run on a ChunkPool of `threads` workers (RunStep): a step reads only the file
// and the selection, and its schemas and channels join the reader's when it is taken.
class McapReader : public DriveReader {
 public:
  McapReader(const std::string& path, unsigned threads)
      : path_(path), file_(path), threads_(threads) {
    const mcap::Opening opening = mcap::OpenFile(path_, file_);
    profile_ = opening.profile;
    data_start_ = opening.data_start;
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
    pool_.reset();  // before the selection its jobs read changes
    selected_ = std::move(selected);
    encoding_ = encoding;
    topic_ = topic;
    first_chunk_ = 1;
    last_chunk_ = UINT64_MAX;
    ResetWalk();
  }

  std::vector<std::string> ListingDamage() override { return listing_damage_; }

  uint64_t ChunkCount() override {
    if (indexed_) return chunks_.size();
    ListScan();
    return scan_chunk_count_;
  }

  bool ChunksIndexed() override { return indexed_; }

  void SelectChunks(uint64_t first, uint64_t last) override {
    if (selected_.empty()) throw IoError(path_, "SelectChunks before SelectTopic");
    pool_.reset();
    CheckChunkRange(path_, "drive", first, last, ChunkCount());
    first_chunk_ = first;
    last_chunk_ = last;
    ResetWalk();
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

  ~McapReader() override { pool_.reset(); }

 private:
  RecordState RecordAt(uint64_t pos, uint8_t* op, uint64_t* length) const {
    return mcap::RecordAt(file_, pos, op, length);
  }

  // The summary, used when the footer is intact, points at one and its CRC (when set) matches;
  // on any fault the summary is ignored and the file is scanned instead.
  void ReadSummary() {
    const uint64_t tail = mcap::kRecordPrefix + mcap::kFooterContent + mcap::kMagicSize;
    if (file_.size() < data_start_ + tail) return;
    const uint64_t footer_pos = file_.size() - tail;
    const std::vector<uint8_t> footer = file_.Bytes(footer_pos, tail);
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
        block = file_.Bytes(at, std::min<uint64_t>(kCrcBlock, end - at));
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
        const std::vector<uint8_t> bytes = file_.Bytes(content, length);
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
            const uint16_t id = map.U16("channel id");
            c.channels.insert(id);
            c.message_indexes[id] = map.U64("message index offset");
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

  static void ParseSchema(In* r, std::map<uint16_t, std::string>* schemas) {
    const uint16_t id = r->U16("schema id");
    std::string name = r->Str("schema name");
    if (id != 0) schemas->emplace(id, std::move(name));  // id 0 is invalid: ignored
  }
  static void ParseChannel(In* r, std::map<uint16_t, Channel>* channels) {
    const uint16_t id = r->U16("channel id");
    Channel c;
    c.schema_id = r->U16("channel schema_id");
    c.topic = r->Str("channel topic");
    c.encoding = r->Str("channel message_encoding");
    channels->emplace(id, std::move(c));
  }

  // Topics and counts by a scan of the whole file when the summary did not give them, the
  // damage it meets in listing_damage_.
  void LoadTopics() {
    if (topics_loaded_) return;
    counts_.clear();
    listing_damage_.clear();
    Scan scan{data_start_, 0};
    std::string damage;
    const Sink count = [this](uint16_t channel, uint64_t, const uint8_t*, size_t) {
      ++counts_[channel];
    };
    const Defs defs{&schemas_, &channels_};
    bool more = true;
    while (more) {
      more = ScanStep(&scan, count, &damage, defs);
      if (!damage.empty()) listing_damage_.push_back(path_ + ": " + damage);
      damage.clear();
    }
    topics_loaded_ = true;
  }

  // The walk from the start of the selected range: pending_, damage_ and the steps emptied, the
  // pool started on the next Advance.
  void ResetWalk() {
    pool_.reset();
    pending_.clear();
    damage_.clear();
    done_ = false;
    sequence_ = 0;
    steps_.clear();
    counted_steps_ = 0;
  }

  // The steps of the selected range, and the messages before it counted into sequence_: an
  // indexed file's chunks holding a selected channel; a scanned file's records, those before the
  // range first (their messages counted, their damage that of another range).
  void PlanSteps() {
    if (indexed_) {
      for (size_t c = 0; c < chunks_.size(); ++c) {
        const uint64_t number = c + 1;
        if (number > last_chunk_) break;
        bool wanted = chunks_[c].channels.empty();
        for (uint16_t id : selected_) wanted = wanted || chunks_[c].channels.count(id) > 0;
        if (!wanted) continue;
        Step step;
        step.chunk = c;
        step.owner = number;
        step.is_chunk = true;
        if (number < first_chunk_) {
          sequence_ += CountIndexedChunk(step);
          continue;
        }
        steps_.push_back(step);
      }
      return;
    }
    ListScan();
    for (const Step& step : scan_steps_) {
      const uint64_t owner = std::max<uint64_t>(step.owner, 1);
      if (owner > last_chunk_) break;
      if (owner < first_chunk_) ++counted_steps_;
      steps_.push_back(step);
    }
  }

  // The selected channels' messages in an indexed chunk before the range: the sum of their
  // message index records' entries when every one of them is intact, else the messages a read
  // of the chunk gives.
  uint64_t CountIndexedChunk(const Step& step) {
    const ChunkRef& c = chunks_[step.chunk];
    uint64_t count = 0;
    bool intact = !c.channels.empty();
    for (uint16_t id : selected_) {
      if (!intact) break;
      const auto at = c.message_indexes.find(id);
      if (at == c.message_indexes.end()) continue;
      uint8_t op = 0;
      uint64_t length = 0;
      if (at->second < data_start_ || at->second > file_.size() ||
          RecordAt(at->second, &op, &length) != kWhole || op != mcap::kMessageIndex || length < 6) {
        intact = false;
        break;
      }
      uint8_t head[6];
      file_.ReadInto(at->second + mcap::kRecordPrefix, head, sizeof(head));
      In in(head, sizeof(head));
      const uint16_t channel = in.U16("message index channel_id");
      const uint32_t bytes = in.U32("message index records length");
      intact = channel == id && bytes == length - 6 && bytes % 16 == 0;
      count += bytes / 16;
    }
    return intact ? count : RunStep(step).messages.size();
  }

  // The records of a file without a usable summary, from the header on, as ScanStep walks them:
  // the chunk, schema, channel and message records, and the record (or end of file) where a scan
  // stops with damage; the scan ends after it, or at a data end or footer record. Each record's
  // prefix is read, no chunk's content.
  void ListScan() {
    if (listed_) return;
    listed_ = true;
    uint64_t chunks = 0;
    for (uint64_t pos = data_start_;;) {
      uint8_t op = 0;
      uint64_t length = 0;
      const RecordState state = RecordAt(pos, &op, &length);
      Step step;
      step.pos = pos;
      step.chunks_before = chunks;
      if (state == kEndOfFile || state == kCutPrefix) {
        step.owner = chunks;
        scan_steps_.push_back(step);
        break;
      }
      if (op == mcap::kChunk) {
        step.is_chunk = true;
        step.owner = ++chunks;
      } else {
        step.owner = chunks;
      }
      if (state == kCutContent || op == mcap::kChunk || op == mcap::kSchema ||
          op == mcap::kChannel || op == mcap::kMessage)
        scan_steps_.push_back(step);
      if (state == kCutContent || op == mcap::kDataEnd || op == mcap::kFooter) break;
      pos += mcap::kRecordPrefix + length;
    }
    scan_chunk_count_ = chunks;
  }

  // One step's messages of the selected topic, damage and definitions (ChunkPool's job: reads
  // the file, selected_, chunks_ and scan_steps_, writes only its result).
  StepResult RunStep(const Step& step) const {
    StepResult out;
    const Sink keep = [this, &out](uint16_t channel, uint64_t time, const uint8_t* data,
                                   size_t size) {
      if (selected_.count(channel)) out.messages.push_back({time, {data, data + size}});
    };
    const Defs defs{&out.schemas, &out.channels};
    if (indexed_) {
      out.damage = ReadIndexedChunk(chunks_[step.chunk], step.chunk + 1, keep, defs);
    } else {
      Scan scan{step.pos, step.chunks_before};
      ScanStep(&scan, keep, &out.damage, defs);
    }
    // Within a chunk, by log time; equal times keep their record order.
    std::stable_sort(out.messages.begin(), out.messages.end(),
                     [](const Pending& a, const Pending& b) { return a.log_time < b.log_time; });
    return out;
  }

  // Fills pending_ / damage_ / done_ from the next step's result (the pool started on the first
  // call); a step before the range only counts its messages.
  void Advance() {
    if (!pool_) {
      PlanSteps();
      pool_ = std::make_unique<ChunkPool<StepResult>>(
          steps_.size(), [this](size_t i) { return RunStep(steps_[i]); }, threads_);
    }
    const size_t index = pool_->taken();
    StepResult r;
    if (!pool_->Next(&r)) {
      done_ = true;
      return;
    }
    for (auto& [id, name] : r.schemas) schemas_.emplace(id, std::move(name));
    for (auto& [id, channel] : r.channels) channels_.emplace(id, std::move(channel));
    if (index < counted_steps_) {
      sequence_ += r.messages.size();
      return;
    }
    for (Pending& p : r.messages) pending_.push_back(std::move(p));
    damage_ = std::move(r.damage);
  }

  // An indexed chunk's messages to `sink`; returns its damage ("" when none).
  std::string ReadIndexedChunk(const ChunkRef& c, uint64_t number, const Sink& sink,
                               const Defs& defs) const {
    const std::string where = mcap::ChunkWhere(number, c.offset);
    if (c.offset < data_start_ || c.offset > file_.size() || c.length > file_.size() - c.offset ||
        c.length < mcap::kRecordPrefix) {
      return where + ": the chunk index points past the end of the file (" +
             std::to_string(c.length) + " bytes, the file has " + std::to_string(file_.size()) +
             ")";
    }
    uint8_t op = 0;
    uint64_t length = 0;
    RecordAt(c.offset, &op, &length);
    if (op != mcap::kChunk || length != c.length - mcap::kRecordPrefix)
      return where + ": the chunk index does not point at a chunk record of its length";
    const std::vector<uint8_t> bytes = file_.Bytes(c.offset + mcap::kRecordPrefix, length);
    return mcap::ReadChunk(where, bytes.data(), bytes.size(), false, Visitor(sink, defs));
  }

  // One step of a scan (mcap::ScanRecord) reading the schema, channel and message records.
  bool ScanStep(Scan* scan, const Sink& sink, std::string* damage, const Defs& defs) const {
    return mcap::ScanRecord(file_, scan, {mcap::kSchema, mcap::kChannel, mcap::kMessage},
                            Visitor(sink, defs), damage);
  }

  // A schema or channel record into `defs`, a message record to `sink` (others are skipped).
  static void Record(uint8_t op, In* r, const Sink& sink, const Defs& defs) {
    if (op == mcap::kSchema) {
      ParseSchema(r, defs.schemas);
    } else if (op == mcap::kChannel) {
      ParseChannel(r, defs.channels);
    } else if (op == mcap::kMessage) {
      const uint16_t channel = r->U16("message channel_id");
      r->U32("message sequence");
      const uint64_t log_time = r->U64("message log_time");
      r->U64("message publish_time");
      const size_t n = r->left();
      sink(channel, log_time, r->Take(n, "message data"), n);
    }
  }
  // Record for mcap::ReadChunk.
  static mcap::RecordVisitor Visitor(const Sink& sink, const Defs& defs) {
    return [&sink, defs](uint8_t op, In* r) { Record(op, r, sink, defs); };
  }

  const std::string path_;
  ReadOnlyFile file_;
  std::string profile_;
  uint64_t data_start_ = 0;  // the first byte after the header record

  std::map<uint16_t, std::string> schemas_;  // id -> name
  std::map<uint16_t, Channel> channels_;
  std::map<uint16_t, uint64_t> counts_;
  bool topics_loaded_ = false;
  std::vector<std::string> listing_damage_;  // LoadTopics' scan's
  bool indexed_ = false;                     // chunks_ (from the summary) drive Next
  std::vector<ChunkRef> chunks_;

  const unsigned threads_;
  bool listed_ = false;  // scan_steps_ and scan_chunk_count_ hold ListScan's findings
  std::vector<Step> scan_steps_;
  uint64_t scan_chunk_count_ = 0;

  // The walk of the selected topic over chunks first_chunk_..last_chunk_.
  std::set<uint16_t> selected_;
  std::string topic_;
  MessageEncoding encoding_ = MessageEncoding::kCdr;
  uint64_t first_chunk_ = 1, last_chunk_ = UINT64_MAX;
  uint64_t sequence_ = 0;
  std::vector<Step> steps_;   // PlanSteps'
  size_t counted_steps_ = 0;  // the first steps_, before the range: counted, not yielded
  std::deque<Pending> pending_;
  std::string damage_;
  bool done_ = false;
  std::unique_ptr<ChunkPool<StepResult>> pool_;  // last: its workers read the members above
};

}  // namespace

std::unique_ptr<DriveReader> OpenMcap(const std::string& path, unsigned threads) {
  return std::make_unique<McapReader>(path, threads);
}

}  // namespace lpir
