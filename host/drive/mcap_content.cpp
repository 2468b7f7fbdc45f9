// An MCAP file's whole content (drive_content.h): the data section walked from the header on, one
// record a step (mcap::ScanRecord), its schema, channel, message, metadata and attachment records
// yielded in file order, a chunk's records in their order inside it. A schema or channel record
// repeated with its id is yielded once; an attachment whose CRC is set and does not match, and a
// message on a channel no record before it defines, are damage.
#include <deque>
#include <set>
#include <utility>

#include "host/drive/decompress.h"
#include "host/drive/drive_content.h"
#include "host/drive/mcap_file.h"
#include "host/drive/mcap_records.h"
#include "host/drive/read_only_file.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

using mcap::In;
using mcap::Malformed;

// A Map<string, string>: uint32 byte length, then key and value strings.
DriveMap ReadMap(In* r, const char* field) {
  const uint32_t n = r->U32(field);
  In map(r->Take(n, field), n);
  DriveMap out;
  while (map.left() > 0) {
    std::string key = map.Str(field);
    out.emplace_back(std::move(key), map.Str(field));
  }
  return out;
}

class McapContent : public DriveContent {
 public:
  explicit McapContent(const std::string& path) : path_(path), file_(path) {
    const mcap::Opening opening = mcap::OpenFile(path_, file_);
    profile_ = opening.profile;
    scan_.pos = opening.data_start;
  }

  const std::string& profile() const override { return profile_; }

  ContentStep Next(DriveRecord* record, std::string* problem) override {
    for (;;) {
      if (!queue_.empty()) {
        *record = std::move(queue_.front());
        queue_.pop_front();
        return ContentStep::kRecord;
      }
      if (!damages_.empty()) {
        *problem = path_ + ": " + damages_.front();
        damages_.pop_front();
        return ContentStep::kDamage;
      }
      if (done_) return ContentStep::kEnd;
      std::string damage;
      const auto visit = [this](uint8_t op, In* r) { Visit(op, r); };
      done_ = !mcap::ScanRecord(
          file_, &scan_,
          {mcap::kSchema, mcap::kChannel, mcap::kMessage, mcap::kMetadata, mcap::kAttachment},
          visit, &damage);
      if (!damage.empty()) damages_.push_back(std::move(damage));
    }
  }

 private:
  // One record (outside a chunk or inside one) into queue_, or into damages_ when it is a message
  // of an undefined channel or an attachment with a wrong CRC. Malformed for a record too short
  // for its fields.
  void Visit(uint8_t op, In* r) {
    if (op == mcap::kSchema) {
      DriveSchema s;
      s.id = r->U16("schema id");
      s.name = r->Str("schema name");
      s.encoding = r->Str("schema encoding");
      s.data = r->Str("schema data");
      if (s.id != 0 && schemas_.insert(s.id).second) queue_.push_back(std::move(s));
    } else if (op == mcap::kChannel) {
      DriveChannel c;
      c.id = r->U16("channel id");
      c.schema_id = r->U16("channel schema_id");
      c.topic = r->Str("channel topic");
      c.message_encoding = r->Str("channel message_encoding");
      c.metadata = ReadMap(r, "channel metadata");
      if (channels_.insert(c.id).second) queue_.push_back(std::move(c));
    } else if (op == mcap::kMessage) {
      DriveRecordMessage m;
      m.channel_id = r->U16("message channel_id");
      m.sequence = r->U32("message sequence");
      m.log_time_ns = r->U64("message log_time");
      m.publish_time_ns = r->U64("message publish_time");
      const size_t n = r->left();
      const uint8_t* data = r->Take(n, "message data");
      if (!channels_.count(m.channel_id)) {
        if (orphans_.insert(m.channel_id).second)
          damages_.push_back("a message on channel " + std::to_string(m.channel_id) +
                             ", which no channel record before it defines, left out with every "
                             "later one of that channel");
        return;
      }
      m.data.assign(data, data + n);
      queue_.push_back(std::move(m));
    } else if (op == mcap::kMetadata) {
      DriveMetadata m;
      m.name = r->Str("metadata name");
      m.entries = ReadMap(r, "metadata");
      queue_.push_back(std::move(m));
    } else if (op == mcap::kAttachment) {
      queue_.push_back(ReadAttachment(r));
    }
  }

  // An attachment record: log_time, create_time, name, media_type, uint64-prefixed data, then the
  // CRC-32 of the fields before it (0: none). Malformed when the CRC is set and differs.
  static DriveAttachment ReadAttachment(In* r) {
    const size_t total = r->left();
    DriveAttachment a;
    const uint8_t* start = r->Take(0, "attachment");
    a.log_time_ns = r->U64("attachment log_time");
    a.create_time_ns = r->U64("attachment create_time");
    a.name = r->Str("attachment name");
    a.media_type = r->Str("attachment media_type");
    const uint64_t n = r->U64("attachment data length");
    const uint8_t* data = r->Take(n, "attachment data");
    const size_t covered = total - r->left();
    const uint32_t crc = r->U32("attachment crc");
    if (crc != 0 && Crc32(start, covered) != crc)
      throw Malformed("attachment " + a.name + ": CRC mismatch");
    a.data.assign(data, data + n);
    return a;
  }

  const std::string path_;
  ReadOnlyFile file_;
  std::string profile_;
  mcap::Scan scan_;
  bool done_ = false;
  std::set<uint16_t> schemas_, channels_, orphans_;  // ids yielded; channels reported undefined
  std::deque<DriveRecord> queue_;
  std::deque<std::string> damages_;
};

}  // namespace

std::unique_ptr<DriveContent> OpenMcapContent(const std::string& path) {
  return std::make_unique<McapContent>(path);
}

}  // namespace lpir
