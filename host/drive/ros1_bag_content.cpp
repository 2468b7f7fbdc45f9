// A ROS 1 bag's whole content (drive_content.h): its records walked from the bag header on, in
// file order, each chunk decompressed once and its connection and message records yielded in
// their order inside it; the index records (index data, chunk info, the connections repeated at
// the end) add nothing and are skipped. Channels are numbered in the order their connections are
// first met (a bag's conn ids are not kept: MCAP's are 16 bits); a connection repeated is yielded
// once. A damaged part (ros1_bag_file.h's checks) is kDamage naming the file, the byte or chunk
// and the problem; the walk goes on after it when its record's lengths lie inside the file. A bag
// without an index (NAME.bag.active) may end in the chunk its recorder was writing
// (ros1::UnfinishedChunk): read to the end of the file, as the topic reader reads it.
#include <deque>
#include <map>
#include <set>
#include <utility>

#include "host/drive/drive_content.h"
#include "host/drive/read_only_file.h"
#include "host/drive/ros1_bag_file.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

using ros1::Broken;
using ros1::Fields;

class Ros1BagContent : public DriveContent {
 public:
  explicit Ros1BagContent(const std::string& path) : path_(path), file_(path) {
    ros1::CheckMagic(path_, file_);
    try {
      const ros1::Record r = ros1::ReadRecordAt(file_, ros1::kMagicSize);
      const Fields f = ros1::ReadFields(file_, r, "byte " + std::to_string(r.pos));
      if (f.Op() != ros1::kOpBagHeader || r.data_truncated)
        f.Fail("not a whole bag header record (op 3)");
      unindexed_ = f.U64("index_pos") == 0;
      pos_ = r.end();
    } catch (const Broken& e) {
      throw IoError(path_, std::string("no valid bag header: ") + e.what());
    }
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
      if (pos_ >= file_.size()) return ContentStep::kEnd;
      try {
        Step();
      } catch (const Broken& e) {
        damages_.push_back(e.what());
      }
    }
  }

 private:
  // The record at pos_: its connections and messages queued, pos_ moved past it (to the end of
  // the file when its lengths run past it). Broken for a damaged record, pos_ already moved.
  void Step() {
    const uint64_t at = pos_;
    pos_ = file_.size();  // unless the record's lengths say where the next one starts
    const ros1::Record r = ros1::ReadRecordAt(file_, at);
    if (!r.data_truncated) pos_ = r.end();
    const std::string where = "byte " + std::to_string(at);
    const Fields f = ros1::ReadFields(file_, r, where);
    const uint8_t op = f.Op();
    if (op == ros1::kOpChunk) {
      if (ros1::UnfinishedChunk(file_, r, f, unindexed_)) pos_ = file_.size();
      ReadChunk(at);
    } else if (op == ros1::kOpConnection) {
      const std::vector<uint8_t> data = ros1::ReadData(file_, r);
      AddConnection(f, where, data.data(), data.size());
    } else if (op == ros1::kOpIndexData || op == ros1::kOpChunkInfo) {
      if (r.data_truncated) ros1::ReadData(file_, r);  // throws: the file ends inside it
    } else {
      f.Fail("a record of op " + std::to_string(op) + " outside a chunk, left out");
    }
  }

  // The chunk at `at`: every whole record decompressed there (a truncated uncompressed chunk's
  // too), then its damage, if any.
  void ReadChunk(uint64_t at) {
    const std::string where =
        "chunk " + std::to_string(++chunks_) + " at byte " + std::to_string(at);
    const ros1::LoadedChunk chunk = ros1::LoadChunk(file_, at, where, unindexed_);
    const std::vector<uint8_t>& d = chunk.data;
    try {
      for (size_t pos = 0; pos < d.size();) {
        const std::string in = where + ", offset " + std::to_string(pos);
        const ros1::ChunkRecord r = ros1::RecordInChunk(d, pos, in);
        const uint8_t op = r.fields.Op();
        if (op == ros1::kOpMessage) {
          AddMessage(r.fields, &d[r.data_pos], r.data_len);
        } else if (op == ros1::kOpConnection) {
          AddConnection(r.fields, in, &d[r.data_pos], r.data_len);
        } else {
          r.fields.Fail("a record of op " + std::to_string(op) + " inside a chunk");
        }
        pos = r.data_pos + r.data_len;
      }
    } catch (const Broken& e) {
      if (chunk.damage.empty()) damages_.push_back(e.what());
    }
    if (!chunk.damage.empty()) damages_.push_back(chunk.damage);
  }

  // A connection record (header: conn, topic; data: the connection header) as a channel, and its
  // schema when its (type, message_definition) is new; nothing for a conn already met.
  void AddConnection(const Fields& record, const std::string& where, const uint8_t* data,
                     size_t size) {
    const uint32_t conn = record.U32("conn");
    if (channels_.count(conn)) return;
    const Fields header(where + ", connection header", data, size);
    if (channels_.size() > UINT16_MAX)
      record.Fail("more than 65536 connections; MCAP's channel ids are 16 bits");
    DriveChannel c;
    c.id = uint16_t(channels_.size());
    c.topic = record.String("topic");
    c.message_encoding = "ros1";
    const std::string& type = header.String("type");
    const std::string definition =
        header.Has("message_definition") ? header.String("message_definition") : "";
    auto [schema, fresh] = schemas_.emplace(std::make_pair(type, definition), 0);
    if (fresh) {
      schema->second = uint16_t(schemas_.size());
      queue_.push_back(DriveSchema{schema->second, type, "ros1msg", definition});
    }
    c.schema_id = schema->second;
    for (const auto& [name, value] : header.all())
      if (name != "topic" && name != "type" && name != "message_definition")
        c.metadata.emplace_back(name, value);
    channels_.emplace(conn, Channel{c.id, 0});
    queue_.push_back(std::move(c));
  }

  // A message data record (header: conn, time) on its connection's channel.
  void AddMessage(const Fields& record, const uint8_t* data, size_t size) {
    const uint32_t conn = record.U32("conn");
    const uint64_t time = record.Time("time");
    const auto channel = channels_.find(conn);
    if (channel == channels_.end()) {
      if (orphans_.insert(conn).second)
        damages_.push_back("a message of connection " + std::to_string(conn) +
                           ", which no connection record before it defines, left out with every "
                           "later one of that connection");
      return;
    }
    DriveRecordMessage m;
    m.channel_id = channel->second.id;
    m.sequence = channel->second.messages++;
    m.log_time_ns = m.publish_time_ns = time;
    m.data.assign(data, data + size);
    queue_.push_back(std::move(m));
  }

  struct Channel {
    uint16_t id;
    uint32_t messages;  // yielded so far: the next one's sequence
  };

  const std::string path_;
  const std::string profile_ = "ros1";
  ReadOnlyFile file_;
  bool unindexed_ = false;  // index_pos 0: a recorder that died (its last chunk unfinished)
  uint64_t pos_ = 0;        // the next record
  uint64_t chunks_ = 0;     // chunk records met (numbered from 1, as the topic reader does)
  std::map<uint32_t, Channel> channels_;                             // conn -> its channel
  std::map<std::pair<std::string, std::string>, uint16_t> schemas_;  // (type, definition) -> id
  std::set<uint32_t> orphans_;  // conns whose messages came before any connection record
  std::deque<DriveRecord> queue_;
  std::deque<std::string> damages_;
};

}  // namespace

std::unique_ptr<DriveContent> OpenRos1BagContent(const std::string& path) {
  return std::make_unique<Ros1BagContent>(path);
}

}  // namespace lpir
