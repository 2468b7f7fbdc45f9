// ROS 1 bag format 2.0 reader. The file is "#ROSBAG V2.0\n" then records, each
//   uint32 header_len, header (fields: uint32 field_len, "name=value"), uint32 data_len, data
// with the header's `op` naming the record: 0x03 bag header (index_pos, conn_count, chunk_count),
// 0x05 chunk (compression none|bz2|lz4, size = the uncompressed size; data = message data 0x02
// and connection 0x07 records), 0x04 index data after each chunk (ver 1, conn, count; data =
// count x {time, uint32 offset into the uncompressed chunk}), and at index_pos the connection
// records then 0x06 chunk infos (ver 1, chunk_pos, start_time, end_time, count; data = count x
// {conn, message count}). Integers are little-endian; a time is uint32 sec, uint32 nsec.
//
// Reading, in order:
//   1. Open: the magic, then the bag header record (IoError when either is bad).
//   2. On the first Topics or SelectTopic: the index at index_pos when it is whole and agrees
//      with itself (conn_count connections, chunk_count chunk infos at distinct positions before
//      index_pos, every connection they name defined); else a scan of every record from the
//      start, decompressing each chunk once, which finds the connections and messages and
//      records each damaged part where it lies in the file.
//   3. SelectTopic lists the messages of the topic's connections (from the index data records
//      after each chunk, or from a scan of that chunk when they are missing or disagree with the
//      chunk info) and sorts them by receipt time, ties in file order.
//   4. Next reads each message from its chunk, decompressed a chunk at a time (the last one kept):
//      the chunks in the order Next needs them are ChunkPool jobs (LoadChunk, which reads only the
//      file and the catalogue), decompressed ahead on the pool's workers. With SelectChunks, only
//      the messages of the range's chunks are read; the others only advance the sequence.
// Damage: a damaged part found by a scan is reported once every message that lies before it in
// the file has been yielded; a chunk found damaged only when Next loads it (the indexed case) is
// reported when the first of its messages is due. After damage the reader goes on at the next
// chunk whose position is known: from the chunk infos, or the end of the damaged record when its
// lengths lie inside the file; a scan that meets a record running past the end of the file stops
// there. The complete message records of a truncated uncompressed chunk are still yielded; a
// truncated compressed chunk yields none. A bag without an index (index_pos 0: the recorder died
// before closing it, leaving NAME.bag.active) may end in the chunk it was writing: a chunk record
// whose sizes are still the zeros written before its data, followed by that data. Its data is
// taken to run to the end of the file, as a truncated chunk's: an uncompressed one's complete
// records are yielded, a compressed one is damage. The file is never read whole: a record's bytes
// are read only once its lengths are checked against the bytes left in the file.
#include "host/drive/ros1_bag_reader.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "host/drive/chunk_pool.h"
#include "host/drive/read_only_file.h"
#include "host/drive/ros1_bag_file.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

using ros1::Broken;
using ros1::ChunkRecord;
using ros1::Fields;
using ros1::kMagicSize;
using ros1::kOpBagHeader;
using ros1::kOpChunk;
using ros1::kOpChunkInfo;
using ros1::kOpConnection;
using ros1::kOpIndexData;
using ros1::kOpMessage;
using ros1::LeU32;
using ros1::LoadedChunk;
using ros1::Record;
using ros1::RecordInChunk;
using ros1::TimeNs;

struct Connection {
  std::string topic, type;
};

// One message: when it was received and where its record lies (file order = (chunk, offset)).
struct Entry {
  uint64_t time_ns;
  uint32_t chunk;   // index into chunks_ (sorted by position)
  uint32_t offset;  // of the message data record in the uncompressed chunk
  uint32_t conn;
};

// A damaged part found before reading, at file position (pos, offset): `pos` the byte of the
// record, `offset` the byte inside its uncompressed chunk data.
struct Damage {
  uint64_t pos;
  uint64_t offset;
  std::string problem;
};

class Ros1Bag : public DriveReader {
 public:
  Ros1Bag(const std::string& path, unsigned threads) : path_(path), file_(path), threads_(threads) {
    ros1::CheckMagic(path_, file_);
    try {
      const Record r = ReadRecordAt(kMagicSize);
      const Fields f = ReadFields(r, "byte " + std::to_string(r.pos));
      if (f.Op() != kOpBagHeader) f.Fail("op is " + std::to_string(f.Op()) + ", not bag header 3");
      if (r.data_truncated) f.Fail("the bag header's padding runs past the end of the file");
      index_pos_ = f.U64("index_pos");
      conn_count_ = f.U32("conn_count");
      chunk_count_ = f.U32("chunk_count");
      first_record_ = r.end();
    } catch (const Broken& e) {
      throw IoError(path_, std::string("no valid bag header: ") + e.what());
    }
  }

  std::vector<std::string> ListingDamage() override {
    EnsureCatalogue();
    std::vector<std::string> damage;
    for (const Damage& d : scan_damages_) damage.push_back(d.problem);
    return damage;
  }

  std::vector<std::string> Notes() override {
    EnsureCatalogue();
    std::vector<std::string> notes;
    if (index_pos_ == 0)
      notes.push_back(path_ + ": no index (the recorder died before closing the bag; `rosbag " +
                      "reindex` writes one): its " + std::to_string(chunks_.size()) + " chunk" +
                      (chunks_.size() == 1 ? " was" : "s were") + " scanned");
    if (unfinished_ != UINT32_MAX)
      notes.push_back(path_ + ": " + ChunkWhere(unfinished_) +
                      " is the one the recorder was writing (its sizes never filled in): read "
                      "up to the end of the file");
    return notes;
  }

  std::vector<DriveTopic> Topics() override {
    EnsureCatalogue();
    std::map<std::string, DriveTopic> topics;
    for (const auto& [id, c] : connections_) {
      DriveTopic& t = topics[c.topic];
      if (t.name.empty()) t = DriveTopic{c.topic, c.type, "ros1", 0};
    }
    for (const auto& [id, n] : message_counts_) topics[connections_.at(id).topic].messages += n;
    std::vector<DriveTopic> out;
    for (auto& [name, t] : topics) out.push_back(std::move(t));
    return out;
  }

  ~Ros1Bag() override { pool_.reset(); }

  uint64_t ChunkCount() override {
    EnsureCatalogue();
    return chunks_.size();
  }

  bool ChunksIndexed() override {
    if (!catalogued_ && index_pos_ == 0) return false;  // no index to try: no scan for this
    EnsureCatalogue();
    return indexed_;
  }

  void SelectChunks(uint64_t first, uint64_t last) override {
    if (topic_.empty()) throw IoError(path_, "SelectChunks before SelectTopic");
    pool_.reset();
    CheckChunkRange(path_, "bag", first, last, ChunkCount());
    first_chunk_ = uint32_t(first - 1);
    last_chunk_ = uint32_t(last - 1);
    Restart();
  }

  void SelectTopic(const std::string& topic) override {
    pool_.reset();  // before the catalogue its jobs read changes
    EnsureCatalogue();
    std::set<uint32_t> conns;
    std::string names;
    std::set<std::string> seen;
    for (const auto& [id, c] : connections_) {
      if (c.topic == topic) conns.insert(id);
      if (seen.insert(c.topic).second) names += (names.empty() ? "" : ", ") + c.topic;
    }
    if (conns.empty()) {
      // A bag cut inside its first chunk loses the connections with it: say so.
      const std::string damage =
          scan_damages_.empty()
              ? ""
              : "; its first damage: " + scan_damages_.front().problem.substr(path_.size() + 2);
      throw IoError(path_, "no topic '" + topic + "'; the bag has " +
                               (names.empty() ? std::string("none") : names) + damage);
    }
    topic_ = topic;
    entries_.clear();
    std::vector<Damage> damages;
    if (indexed_) {
      damage_known_.assign(chunks_.size(), false);
      for (uint32_t c = 0; c < chunks_.size(); ++c) {
        bool wanted = false;
        for (const auto& [conn, n] : chunk_counts_[c]) wanted |= n > 0 && conns.count(conn) > 0;
        if (wanted && !ReadChunkIndex(c, conns, &entries_)) {
          std::vector<Entry> all;
          ScanChunk(c, &all, &damages, &damage_known_, false);
          std::map<uint32_t, uint64_t> found;
          for (const Entry& e : all) {
            if (!conns.count(e.conn)) continue;
            entries_.push_back(e);
            ++found[e.conn];
          }
          for (uint32_t conn : conns) {
            const auto info = chunk_counts_[c].find(conn);
            const uint64_t listed = info == chunk_counts_[c].end() ? 0 : info->second;
            if (found[conn] != listed && !damage_known_[c]) {
              damage_known_[c] = true;
              damages.push_back(Damage{chunks_[c], 0,
                                       path_ + ": " + ChunkWhere(c) + ": the chunk info lists " +
                                           std::to_string(listed) + " messages of connection " +
                                           std::to_string(conn) + ", the chunk holds " +
                                           std::to_string(found[conn])});
            }
          }
        }
      }
    } else {
      damage_known_ = scan_damage_known_;
      damages = scan_damages_;
      for (const Entry& e : scan_entries_)
        if (conns.count(e.conn)) entries_.push_back(e);
    }
    std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
      return std::tie(a.time_ns, a.chunk, a.offset) < std::tie(b.time_ns, b.chunk, b.offset);
    });
    PlaceDamages(damages);
    first_chunk_ = 0;
    last_chunk_ = UINT32_MAX;
    Restart();
  }

  DriveStep Next(DriveMessage* message, std::string* problem) override {
    if (!pool_) StartPool();
    for (;;) {
      while (next_damage_ < damages_.size() && damages_[next_damage_].before <= next_entry_) {
        const PlacedDamage& d = damages_[next_damage_++];
        if (InRange(d.chunk)) return Damaged(d.problem, problem);
      }
      if (next_entry_ == entries_.size()) return DriveStep::kEnd;
      const Entry& e = entries_[next_entry_];
      if (!InRange(e.chunk)) {  // another range's: counted as one yielded there
        ++next_entry_;
        ++sequence_;
        continue;
      }
      if (cached_chunk_ != e.chunk) {
        if (!pool_->Next(&cached_) || loads_[pool_->taken() - 1] != e.chunk)
          throw IoError(path_, "internal: the chunk decompressed ahead is not the one needed");
        cached_chunk_ = e.chunk;
      }
      if (!cached_.damage.empty() && !damage_known_[e.chunk]) {
        damage_known_[e.chunk] = true;
        return Damaged(path_ + ": " + cached_.damage, problem);  // the entry is tried again next
      }
      ++next_entry_;
      try {
        ReadMessage(e, message);
        return DriveStep::kMessage;
      } catch (const Broken& b) {
        if (damage_known_[e.chunk]) continue;  // a part of a chunk already reported damaged
        return Damaged(path_ + ": " + b.what(), problem);
      }
    }
  }

 private:
  bool InRange(uint32_t chunk) const { return chunk >= first_chunk_ && chunk <= last_chunk_; }

  // The walk from the first message of the range, the pool started again on the next Next.
  void Restart() {
    pool_.reset();
    next_entry_ = next_damage_ = 0;
    sequence_ = 0;
    cached_chunk_ = UINT32_MAX;
    cached_ = LoadedChunk{};
  }

  // loads_: the chunks in the order Next needs them (each run of the range's entries in one
  // chunk one load), then the pool that decompresses them.
  void StartPool() {
    loads_.clear();
    uint32_t last = UINT32_MAX;
    for (const Entry& e : entries_) {
      if (!InRange(e.chunk) || e.chunk == last) continue;
      loads_.push_back(e.chunk);
      last = e.chunk;
    }
    pool_ = std::make_unique<ChunkPool<LoadedChunk>>(
        loads_.size(), [this](size_t k) { return LoadChunk(loads_[k]); }, threads_);
  }

  // kDamage with `what` and how many of the topic's messages came before it.
  DriveStep Damaged(const std::string& what, std::string* problem) const {
    *problem = what + " (after " + std::to_string(sequence_) +
               (sequence_ == 1 ? " message" : " messages") + " of " + topic_ + ")";
    return DriveStep::kDamage;
  }

  // A chunk the recorder was writing when it died (ros1::UnfinishedChunk).
  bool Unfinished(const Record& r, const Fields& f) const {
    return ros1::UnfinishedChunk(file_, r, f, index_pos_ == 0);
  }

  std::string ChunkWhere(uint32_t c) const {
    return "chunk " + std::to_string(c + 1) + " at byte " +
           std::to_string(chunks_[c]);  // 1-based, as MCAP's
  }

  Record ReadRecordAt(uint64_t pos) const { return ros1::ReadRecordAt(file_, pos); }
  Fields ReadFields(const Record& r, const std::string& at) const {
    return ros1::ReadFields(file_, r, at);
  }
  std::vector<uint8_t> ReadData(const Record& r) const { return ros1::ReadData(file_, r); }
  // A connection record's header and data (the connection header: topic, type, md5sum, ...).
  std::pair<uint32_t, Connection> ParseConnection(const Fields& f, const std::string& at,
                                                  const uint8_t* data, size_t size) {
    const uint32_t id = f.U32("conn");
    Connection c;
    c.topic = f.String("topic");
    const Fields header(at + ", connection header", data, size);
    c.type = header.String("type");
    return {id, c};
  }

  // Step 2: the index when it is usable, else the scan. A bag header that points at an index
  // which is not usable is damage (reported after the scan's messages) unless the scan already
  // met the end of the file inside a record.
  void EnsureCatalogue() {
    if (catalogued_) return;
    catalogued_ = true;
    std::string why;
    if (ReadIndex(&why)) {
      indexed_ = true;
      return;
    }
    connections_.clear();
    chunks_.clear();
    chunk_counts_.clear();
    message_counts_.clear();
    const bool whole = ScanFile();
    if (index_pos_ != 0 && whole)
      scan_damages_.push_back(Damage{file_.size(), 0,
                                     path_ + ": the index at byte " + std::to_string(index_pos_) +
                                         " is not usable (" + why + "); the chunks were scanned"});
  }

  // The connections and chunk infos at index_pos; false with `why` when they are absent, damaged
  // or disagree with the bag header.
  bool ReadIndex(std::string* why) {
    const uint64_t size = file_.size();
    if (index_pos_ == 0) return false;
    if (index_pos_ < first_record_ || index_pos_ > size) {
      *why = index_pos_ > size ? "the file ends at byte " + std::to_string(size) + ", before it"
                               : "it would lie inside the bag header";
      return false;
    }
    std::vector<std::pair<uint64_t, std::map<uint32_t, uint32_t>>> infos;
    try {
      for (uint64_t pos = index_pos_; pos < size;) {
        const Record r = ReadRecordAt(pos);
        const std::string at = "byte " + std::to_string(pos);
        const Fields f = ReadFields(r, at);
        const std::vector<uint8_t> data = ReadData(r);
        if (f.Op() == kOpConnection) {
          auto [id, c] = ParseConnection(f, at, data.data(), data.size());
          if (!connections_.emplace(id, c).second) {
            *why = "connection " + std::to_string(id) + " defined twice";
            return false;
          }
        } else if (f.Op() == kOpChunkInfo) {
          const uint64_t chunk_pos = f.U64("chunk_pos");
          const uint32_t count = f.U32("count");
          f.Time("start_time");
          f.Time("end_time");
          if (f.U32("ver") != 1 || chunk_pos < first_record_ || chunk_pos >= index_pos_ ||
              data.size() != uint64_t(count) * 8) {
            *why = at + ": a chunk info of another version, size or chunk position";
            return false;
          }
          std::map<uint32_t, uint32_t> counts;
          for (uint32_t k = 0; k < count; ++k) {
            if (!counts.emplace(LeU32(&data[8 * k]), LeU32(&data[8 * k + 4])).second) {
              *why = at + ": a chunk info names a connection twice";
              return false;
            }
          }
          infos.emplace_back(chunk_pos, std::move(counts));
        } else {
          *why = at + ": a record of op " + std::to_string(f.Op()) + " in the index";
          return false;
        }
        pos = r.end();
      }
    } catch (const Broken& e) {
      *why = e.what();
      return false;
    }
    if (connections_.size() != conn_count_ || infos.size() != chunk_count_) {
      *why = std::to_string(connections_.size()) + " connections and " +
             std::to_string(infos.size()) + " chunk infos, the bag header says " +
             std::to_string(conn_count_) + " and " + std::to_string(chunk_count_);
      return false;
    }
    std::sort(infos.begin(), infos.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t c = 0; c < infos.size(); ++c) {
      if (c > 0 && infos[c].first == infos[c - 1].first) {
        *why = "two chunk infos for the chunk at byte " + std::to_string(infos[c].first);
        return false;
      }
      for (const auto& [conn, n] : infos[c].second) {
        if (!connections_.count(conn)) {
          *why = "a chunk info names connection " + std::to_string(conn) + ", never defined";
          return false;
        }
        message_counts_[conn] += n;
      }
      chunks_.push_back(infos[c].first);
      chunk_counts_.push_back(std::move(infos[c].second));
    }
    return true;
  }

  // The index data records after chunk `c` for the connections in `conns`, appended to
  // `entries`; false (nothing appended) when they are damaged or disagree with the chunk info.
  bool ReadChunkIndex(uint32_t c, const std::set<uint32_t>& conns, std::vector<Entry>* entries) {
    std::vector<Entry> found;
    try {
      const Record chunk = ReadRecordAt(chunks_[c]);
      const Fields cf = ReadFields(chunk, ChunkWhere(c));
      if (cf.Op() != kOpChunk || chunk.data_truncated) return false;
      const uint32_t chunk_size = cf.U32("size");
      std::set<uint32_t> seen;
      uint64_t pos = chunk.end();
      for (size_t k = 0; k < chunk_counts_[c].size(); ++k) {
        const Record r = ReadRecordAt(pos);
        const Fields f = ReadFields(r, "byte " + std::to_string(pos));
        pos = r.end();
        if (f.Op() != kOpIndexData || f.U32("ver") != 1 || r.data_truncated) return false;
        const uint32_t conn = f.U32("conn"), count = f.U32("count");
        const auto info = chunk_counts_[c].find(conn);
        if (info == chunk_counts_[c].end() || info->second != count || !seen.insert(conn).second ||
            r.data_len != uint64_t(count) * 12)
          return false;
        if (!conns.count(conn)) continue;
        const std::vector<uint8_t> data = ReadData(r);
        for (uint32_t m = 0; m < count; ++m) {
          const uint32_t offset = LeU32(&data[12 * m + 8]);
          if (offset >= chunk_size) return false;
          found.push_back(Entry{TimeNs(&data[12 * m]), c, offset, conn});
        }
      }
    } catch (const Broken&) {
      return false;
    }
    entries->insert(entries->end(), found.begin(), found.end());
    return true;
  }

  // Every record from the start: the connections, the chunks and their messages, the damage.
  // True when the records end exactly at the end of the file.
  bool ScanFile() {
    const uint64_t size = file_.size();
    uint64_t pos = first_record_;
    bool whole = true;  // the records end exactly at the end of the file
    while (pos < size) {
      Record r;
      try {
        r = ReadRecordAt(pos);
      } catch (const Broken& e) {
        scan_damages_.push_back(Damage{pos, 0, path_ + ": " + e.what()});
        whole = false;
        break;
      }
      try {
        ScanTopRecord(r);
      } catch (const Broken& e) {
        scan_damages_.push_back(Damage{pos, 0, path_ + ": " + e.what()});
      }
      if (r.data_truncated) {
        whole = false;
        break;
      }
      if (unfinished_ != UINT32_MAX) break;  // its data runs to the end of the file
      pos = r.end();
    }
    for (const auto& [id, c] : connections_) message_counts_[id];
    std::vector<Entry> kept;
    std::map<uint32_t, std::pair<uint64_t, Entry>> orphans;  // conn -> (count, first)
    for (const Entry& e : scan_entries_) {
      if (connections_.count(e.conn)) {
        kept.push_back(e);
        ++message_counts_[e.conn];
      } else {
        ++orphans.emplace(e.conn, std::make_pair(uint64_t(0), e)).first->second.first;
      }
    }
    for (const auto& [conn, first] : orphans)
      scan_damages_.push_back(Damage{chunks_[first.second.chunk], first.second.offset,
                                     path_ + ": " + ChunkWhere(first.second.chunk) + ", offset " +
                                         std::to_string(first.second.offset) + ": " +
                                         std::to_string(first.first) + " messages of connection " +
                                         std::to_string(conn) +
                                         ", which no connection record defines"});
    scan_entries_ = std::move(kept);
    return whole;
  }

  // One record of the scan outside the chunks. Broken for a malformed one, or one whose data runs
  // past the end of the file (a chunk reports that as its damage).
  void ScanTopRecord(const Record& r) {
    const std::string at = "byte " + std::to_string(r.pos);
    const Fields f = ReadFields(r, at);
    const uint8_t op = f.Op();
    if (op == kOpChunk) {
      if (Unfinished(r, f)) unfinished_ = uint32_t(chunks_.size());
      chunks_.push_back(r.pos);
      scan_damage_known_.push_back(false);
      ScanChunk(uint32_t(chunks_.size() - 1), &scan_entries_, &scan_damages_, &scan_damage_known_,
                true);
    } else if (op == kOpConnection) {
      const std::vector<uint8_t> data = ReadData(r);
      AddConnection(ParseConnection(f, at, data.data(), data.size()), r.pos, 0);
    } else if (op == kOpIndexData || op == kOpChunkInfo) {
      if (r.data_truncated) ReadData(r);  // throws: the file ends inside it
    } else {
      f.Fail("a record of op " + std::to_string(op) +
             (op == kOpMessage     ? " (message data) outside a chunk"
              : op == kOpBagHeader ? " (bag header) after the first"
                                   : ", which bag 2.0 does not define"));
    }
  }

  void AddConnection(const std::pair<uint32_t, Connection>& c, uint64_t pos, uint64_t offset) {
    auto [it, added] = connections_.emplace(c.first, c.second);
    if (!added && (it->second.topic != c.second.topic || it->second.type != c.second.type))
      scan_damages_.push_back(Damage{pos, offset,
                                     path_ + ": byte " + std::to_string(pos) + ": connection " +
                                         std::to_string(c.first) + " redefined as " +
                                         c.second.topic + " (" + c.second.type + "), was " +
                                         it->second.topic + " (" + it->second.type + ")"});
  }

  // Chunk `c` decompressed (step 4, and the scans of steps 2 and 3).
  LoadedChunk LoadChunk(uint32_t c) const {
    return ros1::LoadChunk(file_, chunks_[c], ChunkWhere(c), index_pos_ == 0);
  }
  // The records of chunk `c` (step 2's scan, or step 3 when its index data is unusable): its
  // messages to `entries`, its connections registered when `add_connections`, its damage to
  // `damages` and marked in `known`. The first malformed record ends the chunk; in a chunk
  // whose data is damaged the records that break off are part of that one damage.
  void ScanChunk(uint32_t c, std::vector<Entry>* entries, std::vector<Damage>* damages,
                 std::vector<bool>* known, bool add_connections) {
    const LoadedChunk chunk = LoadChunk(c);
    const std::vector<uint8_t>& d = chunk.data;
    size_t pos = 0;
    try {
      while (pos < d.size()) {
        const std::string at = ChunkWhere(c) + ", offset " + std::to_string(pos);
        const ChunkRecord r = RecordInChunk(d, pos, at);
        const Fields& f = r.fields;
        const size_t data_pos = r.data_pos;
        const uint32_t data_len = r.data_len;
        const uint8_t op = f.Op();
        if (op == kOpMessage) {
          entries->push_back(Entry{f.Time("time"), c, uint32_t(pos), f.U32("conn")});
        } else if (op == kOpConnection) {
          const auto conn = ParseConnection(f, at, &d[data_pos], data_len);
          if (add_connections) AddConnection(conn, chunks_[c], pos);
        } else {
          f.Fail("a record of op " + std::to_string(op) + " inside a chunk");
        }
        pos = data_pos + data_len;
      }
    } catch (const Broken& e) {
      if (chunk.damage.empty())
        damages->push_back(Damage{chunks_[c], pos, path_ + ": " + e.what()});
      (*known)[c] = true;
    }
    if (!chunk.damage.empty()) {
      damages->push_back(Damage{chunks_[c], pos, path_ + ": " + chunk.damage});
      (*known)[c] = true;
    }
  }

  // The message record of `e` from the cached chunk. Broken when it is not there or not a
  // message of e.conn.
  void ReadMessage(const Entry& e, DriveMessage* message) {
    const std::vector<uint8_t>& d = cached_.data;
    const std::string at = ChunkWhere(e.chunk) + ", offset " + std::to_string(e.offset);
    if (e.offset > d.size()) throw Broken(at + ": no message record there");
    const ChunkRecord r = RecordInChunk(d, e.offset, at);
    const Fields& f = r.fields;
    const size_t data_pos = r.data_pos;
    const uint32_t data_len = r.data_len;
    if (f.Op() != kOpMessage || f.U32("conn") != e.conn)
      f.Fail("the index names a message of connection " + std::to_string(e.conn) +
             ", the record there is not one");
    message->sequence = sequence_++;
    message->log_time_ns = e.time_ns;
    message->topic = topic_;
    message->encoding = MessageEncoding::kRos1;
    message->data.assign(d.begin() + data_pos, d.begin() + data_pos + data_len);
  }

  // damages_: each damage with the number of sorted entries to yield before it, so that every
  // message lying before it in the file has been yielded by then, and the chunk it belongs to.
  void PlaceDamages(const std::vector<Damage>& damages) {
    damages_.clear();
    // The entries in file order, each with its place in the yield order.
    std::vector<std::pair<std::pair<uint64_t, uint64_t>, size_t>> by_file(entries_.size());
    for (size_t i = 0; i < entries_.size(); ++i)
      by_file[i] = {{chunks_[entries_[i].chunk], entries_[i].offset}, i};
    std::sort(by_file.begin(), by_file.end());
    std::vector<size_t> last(by_file.size());  // last[k]: the latest place among by_file[0..k]
    for (size_t k = 0; k < by_file.size(); ++k)
      last[k] = std::max(by_file[k].second, k ? last[k - 1] : 0);
    std::vector<std::tuple<size_t, uint64_t, uint64_t, std::string>> placed;
    for (const Damage& d : damages) {
      const auto key = std::make_pair(d.pos, d.offset);
      const size_t before =
          std::lower_bound(by_file.begin(), by_file.end(), key,
                           [](const auto& a, const auto& k) { return a.first < k; }) -
          by_file.begin();
      placed.emplace_back(before == 0 ? 0 : last[before - 1] + 1, d.pos, d.offset, d.problem);
    }
    std::stable_sort(placed.begin(), placed.end(), [](const auto& a, const auto& b) {
      return std::tie(std::get<0>(a), std::get<1>(a), std::get<2>(a)) <
             std::tie(std::get<0>(b), std::get<1>(b), std::get<2>(b));
    });
    for (auto& p : placed) {
      // its chunk: the last one starting at or before it (the first one: before every chunk)
      const size_t after =
          std::upper_bound(chunks_.begin(), chunks_.end(), std::get<1>(p)) - chunks_.begin();
      damages_.push_back(PlacedDamage{std::get<0>(p), uint32_t(after == 0 ? 0 : after - 1),
                                      std::move(std::get<3>(p))});
    }
  }

  // A damage in the yield order: reported once `before` entries are past, by the range holding
  // `chunk`.
  struct PlacedDamage {
    size_t before;
    uint32_t chunk;
    std::string problem;
  };

  std::string path_;
  ReadOnlyFile file_;
  const unsigned threads_;
  uint64_t index_pos_ = 0, first_record_ = 0;
  uint32_t conn_count_ = 0, chunk_count_ = 0;

  bool catalogued_ = false, indexed_ = false;
  std::map<uint32_t, Connection> connections_;
  std::vector<uint64_t> chunks_;                            // chunk record positions, ascending
  std::vector<std::map<uint32_t, uint32_t>> chunk_counts_;  // indexed: conn -> messages per chunk
  std::map<uint32_t, uint64_t> message_counts_;             // conn -> messages
  // The scan's findings (unindexed), for every topic.
  std::vector<Entry> scan_entries_;
  std::vector<Damage> scan_damages_;
  std::vector<bool> scan_damage_known_;
  uint32_t unfinished_ = UINT32_MAX;  // the chunk (index) a dead recorder was writing, if any

  // The selected topic.
  std::string topic_;
  std::vector<Entry> entries_;  // in yield order
  std::vector<PlacedDamage> damages_;
  std::vector<bool> damage_known_;                      // per chunk: its damage is reported
  uint32_t first_chunk_ = 0, last_chunk_ = UINT32_MAX;  // the range, as indexes into chunks_
  size_t next_entry_ = 0, next_damage_ = 0;
  uint64_t sequence_ = 0;
  uint32_t cached_chunk_ = UINT32_MAX;
  LoadedChunk cached_;
  std::vector<uint32_t> loads_;                   // StartPool's
  std::unique_ptr<ChunkPool<LoadedChunk>> pool_;  // last: its workers read the members above
};

}  // namespace

std::unique_ptr<DriveReader> OpenRos1Bag(const std::string& path, unsigned threads) {
  return std::make_unique<Ros1Bag>(path, threads);
}

}  // namespace lpir
