// A ROS 2 bag folder's whole content (drive_content.h): its files (ListBagFiles: metadata.yaml's
// order, else their numbers) walked one after another, each by its own content reader, as one
// drive. A schema met again in a later file (same name, encoding and data) keeps the id it was
// yielded with, and so does a channel (same topic, encoding, schema and metadata): each is
// yielded once, and every message names the channel as first yielded. A file's metadata record
// equal to one already yielded (rosbag2 repeats its own in every file) is left out. A file that
// cannot be opened is damage at its place, naming it; the files after it are still read.
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "host/drive/bag_folder.h"
#include "host/drive/drive_content.h"
#include "host/io/io_error.h"

namespace lpir {
namespace {

class BagFolderContent : public DriveContent {
 public:
  explicit BagFolderContent(const std::string& path) : files_(ListBagFiles(path).files) {
    // the profile is the first file's that opens: every file of one bag shares it
    std::string first_error;
    for (const std::string& file : files_) {
      try {
        profile_ = OpenDriveContent(file)->profile();
        return;
      } catch (const IoError& e) {
        if (first_error.empty()) first_error = e.what();
      }
    }
    throw IoError(path, "not one file of the bag can be read; the first: " + first_error);
  }

  const std::string& profile() const override { return profile_; }

  ContentStep Next(DriveRecord* record, std::string* problem) override {
    for (;;) {
      if (!content_) {
        if (file_ >= files_.size()) return ContentStep::kEnd;
        schema_ids_.clear();
        channel_ids_.clear();
        before_ = messages_;
        try {
          const std::string& file = files_[file_++];
          db3_ = DriveFormatOf(file) == DriveFormat::kDb3;
          content_ = OpenDriveContent(file);
        } catch (const IoError& e) {
          *problem = e.what();
          return ContentStep::kDamage;
        }
      }
      const ContentStep step = content_->Next(record, problem);
      if (step == ContentStep::kDamage) return step;
      if (step == ContentStep::kEnd) {
        content_.reset();
        continue;
      }
      if (Renumber(record)) return ContentStep::kRecord;
    }
  }

 private:
  // `record` of the current file with the bag's ids; false when it is one yielded already.
  bool Renumber(DriveRecord* record) {
    if (auto* s = std::get_if<DriveSchema>(record)) {
      const auto key = std::make_tuple(s->name, s->encoding, s->data);
      const auto [at, fresh] = schemas_.emplace(key, uint16_t(schemas_.size() + 1));
      schema_ids_[s->id] = at->second;
      s->id = at->second;
      return fresh;
    }
    if (auto* c = std::get_if<DriveChannel>(record)) {
      const auto schema = schema_ids_.find(c->schema_id);
      c->schema_id = schema == schema_ids_.end() ? 0 : schema->second;
      const auto key = std::make_tuple(c->topic, c->message_encoding, c->schema_id, c->metadata);
      const auto [at, fresh] = channels_.emplace(key, uint16_t(channels_.size()));
      channel_ids_[c->id] = at->second;
      c->id = at->second;
      return fresh;
    }
    if (auto* m = std::get_if<DriveRecordMessage>(record)) {
      m->channel_id = channel_ids_.at(m->channel_id);  // a channel before its messages
      // a .db3's sequence is the message's place among its topic's in that file: counted on
      // across the files; an MCAP's is as stored
      if (db3_) m->sequence += before_[m->channel_id];
      ++messages_[m->channel_id];
      return true;
    }
    if (const auto* meta = std::get_if<DriveMetadata>(record))
      return metadata_.emplace(meta->name, meta->entries).second;
    return true;
  }

  const std::vector<std::string> files_;
  std::string profile_;
  size_t file_ = 0;                        // the next file to open
  std::unique_ptr<DriveContent> content_;  // the file being walked
  bool db3_ = false;                       // it is a .db3
  std::map<std::tuple<std::string, std::string, std::string>, uint16_t> schemas_;
  std::map<std::tuple<std::string, std::string, uint16_t, DriveMap>, uint16_t> channels_;
  std::map<uint16_t, uint16_t> schema_ids_, channel_ids_;  // the file's id -> the bag's
  std::map<uint16_t, uint32_t> messages_;                  // the bag's channel -> messages so far
  std::map<uint16_t, uint32_t> before_;                    // ... in the files before this one
  std::set<std::pair<std::string, DriveMap>> metadata_;    // yielded
};

}  // namespace

std::unique_ptr<DriveContent> OpenBagFolderContent(const std::string& path) {
  return std::make_unique<BagFolderContent>(path);
}

}  // namespace lpir
