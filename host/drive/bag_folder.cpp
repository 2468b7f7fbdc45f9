// A ROS 2 bag folder read as one drive (see bag_folder.h). Open: metadata.yaml's file list (or
// the files by number), each file opened by OpenDrive. Next walks the files in turn, selecting
// the topic in each as its turn comes; a message's sequence is its file's plus the messages
// before that file (those yielded in a whole run; the listed counts under SelectChunks, where
// the files before the range are not read).
#include "host/drive/bag_folder.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#include "host/drive/bag_metadata.h"
#include "host/drive/chunk_pool.h"
#include "host/drive/mini_yaml.h"
#include "host/io/io_error.h"

namespace fs = std::filesystem;

namespace lpir {
namespace {

// metadata.yaml is a few KB; a larger one is not a recorder's.
constexpr uintmax_t kMaxMetadataBytes = uintmax_t(16) << 20;

// `path` without trailing separators ("bag/" -> "bag").
fs::path Trimmed(const std::string& path) {
  fs::path p(path);
  while (p.has_relative_path() && p.filename().empty()) p = p.parent_path();
  return p;
}

// "<prefix>_<N>.mcap" or ".db3": N, or -1 for another name.
long long SplitNumber(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext != ".mcap" && ext != ".db3") return -1;
  const std::string stem = file.stem().string();
  const size_t underscore = stem.rfind('_');
  if (underscore == std::string::npos || underscore + 1 == stem.size()) return -1;
  const std::string digits = stem.substr(underscore + 1);
  if (digits.size() > 12 || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stoll(digits);
}

// metadata.yaml's files in `folder`, resolved, with its topics' counts into *topics; empty
// (with a note) when it is absent or unreadable. IoError for a bag this reader cannot read
// whatever its files hold.
std::vector<std::string> ListedFiles(const std::string& folder_name,
                                     std::vector<BagMetadata::Topic>* topics,
                                     std::vector<std::string>* notes) {
  const fs::path folder(folder_name);
  const std::string path = (folder / "metadata.yaml").string();
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    notes->push_back(folder_name +
                     ": no metadata.yaml (a recorder that stopped before writing it?): its "
                     "files are read in the order of their numbers");
    return {};
  }
  BagMetadata m;
  try {
    const uintmax_t size = fs::file_size(path, ec);
    if (ec) throw YamlError(ec.message());
    if (size > kMaxMetadataBytes)
      throw YamlError(std::to_string(size) + " bytes, more than a recorder writes");
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in) throw YamlError("cannot be read");
    m = ParseBagMetadata(text.str());
  } catch (const YamlError& e) {
    notes->push_back(path + ": not read (" + e.what() +
                     "): the bag's files are read in the order of their numbers");
    return {};
  }
  const bool compressed = !m.compression_format.empty() && !m.compression_mode.empty() &&
                          m.compression_mode != "NONE" && m.compression_mode != "none";
  if (compressed)
    throw IoError(path, "the bag's " +
                            std::string(m.compression_mode == "MESSAGE" ? "messages" : "files") +
                            " are compressed by rosbag2 (" + m.compression_format + ", " +
                            m.compression_mode +
                            " mode), which this reader does not read: `ros2 bag convert` "
                            "writes an uncompressed copy");
  if (!m.storage_identifier.empty() && m.storage_identifier != "mcap" &&
      m.storage_identifier != "sqlite3")
    throw IoError(
        path, "storage '" + m.storage_identifier + "': this reader reads mcap and sqlite3 bags");
  *topics = m.topics;
  std::vector<std::string> files;
  for (const std::string& rel : m.relative_file_paths) {
    // Since version 4 the paths are relative to the folder; before, to the folder above it.
    fs::path file = folder / rel;
    if (!fs::exists(file, ec) && fs::exists(folder.parent_path() / rel, ec))
      file = folder.parent_path() / rel;
    files.push_back(file.string());
  }
  return files;
}

// The folder's <anything>_<N>.mcap and .db3 files by N (then by name); IoError when it has none.
std::vector<std::string> NumberedFiles(const std::string& folder) {
  std::vector<std::tuple<long long, std::string>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    const long long n = SplitNumber(entry.path().filename());
    if (n >= 0 && entry.is_regular_file(ec)) found.emplace_back(n, entry.path().string());
  }
  std::sort(found.begin(), found.end());
  if (found.empty())
    throw IoError(folder,
                  "a ROS 2 bag folder without a readable metadata.yaml and without files named "
                  "<name>_<N>.mcap or .db3");
  std::vector<std::string> files;
  for (auto& [n, file] : found) files.push_back(std::move(file));
  return files;
}

class BagFolder : public DriveReader {
 public:
  BagFolder(const std::string& path, unsigned threads) : folder_(Trimmed(path).string()) {
    BagFiles listed = ListBagFiles(folder_);
    notes_ = std::move(listed.notes);
    metadata_topics_ = std::move(listed.topics);
    for (const std::string& file : listed.files) {
      Part part;
      part.path = file;
      try {
        part.reader = OpenDrive(file, threads);
      } catch (const IoError& e) {
        part.open_error = e.what();
      }
      parts_.push_back(std::move(part));
    }
    for (const Part& p : parts_)
      if (p.reader) return;
    throw IoError(folder_,
                  "not one file of the bag can be read; the first: " + parts_.front().open_error);
  }

  std::vector<DriveTopic> Topics() override {
    std::vector<DriveTopic> topics;
    std::map<std::string, size_t> at;
    for (Part& p : parts_) {
      if (!p.reader) continue;
      for (const DriveTopic& t : p.reader->Topics()) {
        auto [it, fresh] = at.emplace(t.name, topics.size());
        if (fresh)
          topics.push_back(t);
        else
          topics[it->second].messages += t.messages;
      }
    }
    if (!counts_checked_) {
      counts_checked_ = true;
      for (const BagMetadata::Topic& listed : metadata_topics_) {
        const auto found = at.find(listed.name);
        const uint64_t held = found == at.end() ? 0 : topics[found->second].messages;
        if (held < listed.messages)
          count_damage_.push_back(MetadataPath() + ": counts " + std::to_string(listed.messages) +
                                  " messages of " + listed.name + ", the bag's files hold " +
                                  std::to_string(held));
      }
    }
    return topics;
  }

  std::vector<std::string> ListingDamage() override {
    std::vector<std::string> damage;
    for (Part& p : parts_) {
      if (!p.reader) {
        damage.push_back(p.open_error);
        continue;
      }
      for (std::string& d : p.reader->ListingDamage()) damage.push_back(std::move(d));
    }
    damage.insert(damage.end(), count_damage_.begin(), count_damage_.end());
    return damage;
  }

  std::vector<std::string> Notes() override {
    std::vector<std::string> notes = notes_;
    for (Part& p : parts_)
      if (p.reader)
        for (std::string& n : p.reader->Notes()) notes.push_back(std::move(n));
    return notes;
  }

  void SelectTopic(const std::string& topic) override {
    bool any = false;
    for (Part& p : parts_) {
      p.has_topic = p.reader && HasTopic(p, topic);
      any = any || p.has_topic;
    }
    if (!any) {
      std::string names;
      for (const DriveTopic& t : Topics()) names += (names.empty() ? "" : ", ") + t.name;
      throw IoError(folder_, "no topic " + topic + " in the bag; it has: " +
                                 (names.empty() ? std::string("none") : names));
    }
    topic_ = topic;
    ranged_ = false;
    Restart();
  }

  uint64_t ChunkCount() override {
    uint64_t count = 0;
    for (Part& p : parts_)
      if (p.reader) count += p.reader->ChunkCount();
    return count;
  }

  bool ChunksIndexed() override {
    for (Part& p : parts_)
      if (p.reader && !p.reader->ChunksIndexed()) return false;
    return ChunkCount() > 0;
  }

  void SelectChunks(uint64_t first, uint64_t last) override {
    if (topic_.empty()) throw IoError(folder_, "SelectChunks before SelectTopic");
    CheckChunkRange(folder_, "bag", first, last, ChunkCount());
    uint64_t before = 0, offset = 0;  // the chunks and the topic's messages of the files before
    for (Part& p : parts_) {
      const uint64_t chunks = p.reader ? p.reader->ChunkCount() : 0;
      p.first = std::max(first, before + 1) - before;
      p.last = std::min(last, before + chunks) - std::min(last, before);
      p.in_range = p.last >= p.first && p.last > 0;
      // a file without chunks (one that cannot be opened) is reported by the range holding the
      // chunk before it
      p.reports_open_error = !p.reader && std::max<uint64_t>(before, 1) >= first &&
                             std::max<uint64_t>(before, 1) <= last;
      p.offset = offset;
      if (p.has_topic) offset += TopicCount(p);
      before += chunks;
    }
    ranged_ = true;
    Restart();
  }

  DriveStep Next(DriveMessage* message, std::string* problem) override {
    if (topic_.empty()) throw IoError(folder_, "Next before SelectTopic");
    while (part_ < parts_.size()) {
      Part& p = parts_[part_];
      if (!p.reader) {
        const bool report = ranged_ ? p.reports_open_error : true;
        ++part_;
        if (!report) continue;
        *problem = p.open_error;
        return DriveStep::kDamage;
      }
      if (!p.has_topic || (ranged_ && !p.in_range)) {
        ++part_;
        continue;
      }
      if (!started_) {
        started_ = true;
        yielded_ = 0;
        try {
          p.reader->SelectTopic(topic_);
          if (ranged_) p.reader->SelectChunks(p.first, p.last);
        } catch (const IoError& e) {
          EndPart();
          *problem = e.what();
          return DriveStep::kDamage;
        }
      }
      const DriveStep step = p.reader->Next(message, problem);
      if (step == DriveStep::kMessage) {
        message->sequence += ranged_ ? p.offset : offset_;
        ++yielded_;
        return step;
      }
      if (step == DriveStep::kDamage) return step;
      EndPart();
    }
    return DriveStep::kEnd;
  }

 private:
  struct Part {
    std::string path;
    std::unique_ptr<DriveReader> reader;  // null when the file could not be opened
    std::string open_error;               // then: why, naming the file
    bool has_topic = false;
    // SelectChunks: the file's share of the range (its own chunk numbers), whether it has one,
    // the topic's messages in the files before it, and whether this range reports open_error.
    uint64_t first = 0, last = 0, offset = 0;
    bool in_range = false, reports_open_error = false;
  };

  std::string MetadataPath() const { return (fs::path(folder_) / "metadata.yaml").string(); }

  // Whether file `p` holds `topic` (true when its topics cannot be listed: its SelectTopic then
  // decides, as damage).
  static bool HasTopic(Part& p, const std::string& topic) {
    try {
      for (const DriveTopic& t : p.reader->Topics())
        if (t.name == topic) return true;
      return false;
    } catch (const IoError&) {
      return true;
    }
  }
  uint64_t TopicCount(Part& p) const {
    try {
      for (const DriveTopic& t : p.reader->Topics())
        if (t.name == topic_) return t.messages;
    } catch (const IoError&) {
    }
    return 0;
  }

  void Restart() {
    part_ = 0;
    started_ = false;
    offset_ = 0;
    yielded_ = 0;
  }
  void EndPart() {
    offset_ += yielded_;
    yielded_ = 0;
    started_ = false;
    ++part_;
  }

  std::string folder_;
  std::vector<Part> parts_;
  std::vector<std::string> notes_;
  std::vector<BagMetadata::Topic> metadata_topics_;
  bool counts_checked_ = false;
  std::vector<std::string> count_damage_;

  std::string topic_;
  bool ranged_ = false;
  size_t part_ = 0;       // the file being read
  bool started_ = false;  // its topic selected
  uint64_t offset_ = 0;   // whole run: the messages yielded by the files before it
  uint64_t yielded_ = 0;  // by it so far
};

}  // namespace

BagFiles ListBagFiles(const std::string& path) {
  BagFiles out;
  const std::string folder = Trimmed(path).string();
  out.files = ListedFiles(folder, &out.topics, &out.notes);
  if (out.files.empty()) {
    out.files = NumberedFiles(folder);
    std::string names;
    for (const std::string& f : out.files)
      names += (names.empty() ? "" : ", ") + fs::path(f).filename().string();
    out.notes.back() += ": " + names;
  }
  return out;
}

bool IsBagFolder(const std::string& path) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return false;
  const fs::path folder = Trimmed(path);
  if (fs::exists(folder / "metadata.yaml", ec)) return true;
  const std::string name = folder.filename().string();
  return fs::is_regular_file(folder / (name + "_0.mcap"), ec) ||
         fs::is_regular_file(folder / (name + "_0.db3"), ec);
}

std::unique_ptr<DriveReader> OpenBagFolder(const std::string& path, unsigned threads) {
  return std::make_unique<BagFolder>(path, threads);
}

}  // namespace lpir
