// segment's frame sources (see frame_source.h).
#include "apps/cli/frame_source.h"

#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "host/io/io_error.h"

namespace lpir {
namespace {

bool IsPointCloud2(const DriveTopic& t) {
  const std::string suffix = "/PointCloud2";
  return t.type.size() >= suffix.size() &&
         t.type.compare(t.type.size() - suffix.size(), suffix.size(), suffix) == 0 &&
         t.type.rfind("sensor_msgs/", 0) == 0;
}

// "a (type, N messages), b (...)".
std::string ListTopics(const std::vector<DriveTopic>& topics) {
  std::string list;
  for (const DriveTopic& t : topics)
    list += (list.empty() ? "" : ", ") + t.name + " (" + t.type + ", " +
            std::to_string(t.messages) + " messages)";
  return list.empty() ? "none" : list;
}

class FileSource : public FrameSource {
 public:
  FileSource(std::vector<std::string> files, ReadOptions read)
      : files_(std::move(files)), read_(read) {}
  size_t count() const override { return files_.size(); }
  const char* unit() const override { return "file"; }
  SourceStep Next(FrameInput* in, std::string* error) override {
    if (next_ == files_.size()) return SourceStep::kEnd;
    const std::string& file = files_[next_++];
    *in = FrameInput{};
    in->input = file;
    in->stem = std::filesystem::path(file).stem().string();
    try {
      in->cloud = ReadCloud(file, read_, &in->note);
      return SourceStep::kFrame;
    } catch (const IoError& e) {  // names the file already
      *error = e.what();
    } catch (const std::exception& e) {
      *error = file + ": " + e.what();
    }
    return SourceStep::kFailed;
  }

 private:
  std::vector<std::string> files_;
  ReadOptions read_;
  size_t next_ = 0;
};

class DriveSource : public FrameSource {
 public:
  DriveSource(std::string drive, std::unique_ptr<DriveReader> reader, std::string topic,
              ChunkRange chunks, size_t count, bool keep)
      : drive_(std::move(drive)),
        reader_(std::move(reader)),
        topic_(std::move(topic)),
        count_(count),
        keep_(keep) {
    reader_->SelectTopic(topic_);
    if (chunks.first != 0) reader_->SelectChunks(chunks.first, chunks.last);
  }
  size_t count() const override { return count_; }
  const char* unit() const override { return "message"; }
  SourceStep Next(FrameInput* in, std::string* error) override {
    *in = FrameInput{};
    error->clear();
    in->input = drive_;
    in->from_drive = true;
    in->topic = topic_;
    DriveMessage& m = in->message;
    const DriveStep step = reader_->Next(&m, error);
    if (step == DriveStep::kEnd) return SourceStep::kEnd;
    if (step == DriveStep::kDamage) return SourceStep::kFailed;
    in->has_message = true;
    in->sequence = m.sequence;
    in->log_time_ns = m.log_time_ns;
    const std::string where = drive_ + ": " + topic_ + " message " + std::to_string(m.sequence);
    try {
      // DecodeDriveCloud's two steps, keeping the message for its stamp
      PointCloud2 msg = m.encoding == MessageEncoding::kCdr
                            ? ParseCdrPointCloud2(where, m.data.data(), m.data.size())
                            : ParseRos1PointCloud2(where, m.data.data(), m.data.size());
      in->stamp_ns = msg.stamp_ns();
      char stem[48];
      std::snprintf(stem, sizeof(stem), "%06llu_%lld", static_cast<unsigned long long>(m.sequence),
                    static_cast<long long>(in->stamp_ns));
      in->stem = stem;
      in->cloud = CloudFromPointCloud2(where, msg);
      if (keep_) in->cloud2 = std::move(msg);
    } catch (const IoError& e) {
      *error = e.what();
    } catch (const std::exception& e) {
      *error = where + ": " + e.what();
    }
    if (!keep_) m.data = {};
    return error->empty() ? SourceStep::kFrame : SourceStep::kFailed;
  }

 private:
  std::string drive_;
  std::unique_ptr<DriveReader> reader_;
  std::string topic_;
  size_t count_;
  bool keep_;
};

class ReadAheadSource : public FrameSource {
 public:
  explicit ReadAheadSource(std::unique_ptr<FrameSource> source)
      : source_(std::move(source)), reader_([this] { Read(); }) {}
  ~ReadAheadSource() override {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    reader_.join();
  }
  size_t count() const override { return source_->count(); }
  const char* unit() const override { return source_->unit(); }
  SourceStep Next(FrameInput* in, std::string* error) override {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return ready_.has_value(); });
    Slot slot = std::move(*ready_);
    ready_.reset();
    lock.unlock();
    changed_.notify_all();
    if (slot.exception) std::rethrow_exception(slot.exception);
    *in = std::move(slot.in);
    *error = std::move(slot.error);
    return slot.step;
  }

 private:
  struct Slot {
    FrameInput in;
    std::string error;
    SourceStep step = SourceStep::kEnd;
    std::exception_ptr exception;
  };

  // The second thread: reads a frame, waits until the last one was taken, hands it over; ends
  // after the source's end or an exception, or when the source is destroyed.
  void Read() {
    for (;;) {
      Slot slot;
      try {
        slot.step = source_->Next(&slot.in, &slot.error);
      } catch (...) {
        slot.exception = std::current_exception();
      }
      const bool last = slot.step == SourceStep::kEnd || slot.exception;
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return stop_ || !ready_.has_value(); });
      if (stop_) return;
      ready_ = std::move(slot);
      lock.unlock();
      changed_.notify_all();
      if (last) return;
    }
  }

  std::unique_ptr<FrameSource> source_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<Slot> ready_;
  bool stop_ = false;
  std::thread reader_;  // last: started once everything it uses is built
};

}  // namespace

std::unique_ptr<FrameSource> ReadAhead(std::unique_ptr<FrameSource> source) {
  return std::make_unique<ReadAheadSource>(std::move(source));
}

std::unique_ptr<FrameSource> OpenFileSource(std::vector<std::string> files, ReadOptions read) {
  return std::make_unique<FileSource>(std::move(files), read);
}

std::string ChooseCloudTopic(const std::string& drive, const std::vector<DriveTopic>& topics,
                             const std::string& topic, const std::vector<std::string>& damage) {
  // "; what could be read before it is damaged (<the first damage>) has <topics>"
  const std::string where =
      damage.empty()
          ? "; the drive has " + ListTopics(topics)
          : " in what could be read: the drive is damaged (" + damage.front() +
                (damage.size() > 1
                     ? ", and " + std::to_string(damage.size() - 1) + " more damaged parts"
                     : std::string()) +
                "); it has " + ListTopics(topics);
  if (!topic.empty()) {
    for (const DriveTopic& t : topics) {
      if (t.name != topic) continue;
      if (!IsPointCloud2(t))
        throw std::invalid_argument(drive + ": topic " + topic + " holds " + t.type +
                                    ", not sensor_msgs/PointCloud2");
      return topic;
    }
    if (!damage.empty()) throw IoError(drive, "no topic " + topic + where);
    throw std::invalid_argument(drive + ": no topic " + topic + where);
  }
  std::vector<DriveTopic> clouds;
  for (const DriveTopic& t : topics)
    if (IsPointCloud2(t)) clouds.push_back(t);
  if (clouds.size() == 1) return clouds[0].name;
  if (clouds.empty()) throw IoError(drive, "no sensor_msgs/PointCloud2 topic" + where);
  throw std::invalid_argument(drive + ": --topic is needed: the drive has " +
                              std::to_string(clouds.size()) +
                              " PointCloud2 topics: " + ListTopics(clouds));
}

std::unique_ptr<FrameSource> OpenDriveSource(const std::string& drive,
                                             std::unique_ptr<DriveReader> reader,
                                             const std::string& topic, ChunkRange chunks,
                                             size_t count, bool keep_messages) {
  return std::make_unique<DriveSource>(drive, std::move(reader), topic, chunks, count,
                                       keep_messages);
}

}  // namespace lpir
