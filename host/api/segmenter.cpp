#include "host/api/segmenter.h"

#include <stdexcept>
#include <utility>

#include "host/api/cpu_pipeline.h"
#include "host/api/sensor_fit.h"
#include "host/api/vulkan_pipeline.h"

namespace lpir {

Backend ParseBackend(const std::string& name) {
  if (name == "auto") return Backend::kAuto;
  if (name == "cpu") return Backend::kCpu;
  if (name == "vulkan") return Backend::kVulkan;
  throw std::invalid_argument("unknown backend '" + name + "' (auto, cpu or vulkan)");
}

size_t DefaultMaxPoints(const SensorProfile& sensor) {
  return sensor.max_points ? sensor.max_points : size_t(sensor.beams) * sensor.width * 2;
}

Segmenter::Segmenter(const SensorProfile& sensor, const SegmenterOptions& options)
    : sensor_(sensor),
      options_(options),
      params_(ParamsForSensor(sensor)),
      tables_(MakeTables(sensor, params_)) {
  if (options_.max_points == 0) options_.max_points = DefaultMaxPoints(sensor);
  if (options_.max_points == 0 || options_.max_points > UINT32_MAX / 16)
    throw std::invalid_argument("max_points must be between 1 and " +
                                std::to_string(UINT32_MAX / 16) + ", not " +
                                std::to_string(options_.max_points));
  if (options.frames_in_flight == 0) throw std::invalid_argument("frames_in_flight is 0");
  if (options.batch == 0) throw std::invalid_argument("batch is 0");
  if (uint64_t(options.frames_in_flight) * options.batch > 4096)
    throw std::invalid_argument("frames_in_flight * batch is over 4096");
  if (options.threads > 1024) throw std::invalid_argument("threads is over 1024");
  slots_ = options.frames_in_flight * options.batch;

  if (options.backend != Backend::kCpu) {
    vk::ContextOptions context_options;
    context_options.device = options.device;
    context_options.validation = options.validation;
    context_options.gpu_only = options.backend == Backend::kAuto && options.device.empty();
    vk::Result<std::unique_ptr<VulkanPipeline>> vulkan = VulkanPipeline::Create(
        context_options, params_, tables_, uint32_t(options_.max_points), slots_, options.batch);
    if (vulkan.ok()) {
      backend_ = Backend::kVulkan;
      backend_note_ = "Vulkan on " + vulkan.value()->device_name();
      pipeline_ = std::move(vulkan).value();
    } else {
      const vk::Error& failure = vulkan.error();
      if (options.backend == Backend::kVulkan || !options.device.empty())
        throw std::runtime_error("the Vulkan backend could not be set up: " + failure.message);
      backend_note_ = (failure.cpu_driver_only ? "CPU reference: "
                       : failure.no_device     ? "CPU reference, no Vulkan device: "
                                               : "CPU reference, the Vulkan set-up failed: ") +
                      failure.message;
    }
  } else {
    backend_note_ = "CPU reference (asked for)";
  }
  options_.threads = 1;
  if (!pipeline_) {
    options_.threads = options.threads ? options.threads : AvailableCores();
    pipeline_ = std::make_unique<CpuPipeline>(params_, tables_, slots_, options_.threads);
  }
  batch_ = pipeline_->batch();
  mount_.mount = MountOf(params_);
  slot_mounts_.assign(slots_, mount_);
}

Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

bool Segmenter::on_cpu_driver() const { return pipeline_->on_cpu_driver(); }

uint64_t Segmenter::device_bytes() const { return pipeline_->device_bytes(); }

void Segmenter::CheckCloud(const Cloud& cloud) const {
  if (!cloud.ring.empty() && cloud.ring.size() != cloud.size())
    throw std::invalid_argument("cloud has " + std::to_string(cloud.ring.size()) +
                                " ring entries for " + std::to_string(cloud.size()) + " points");
  const std::string misfit = SensorFitError(MeasureRings(cloud, sensor_), sensor_);
  if (!misfit.empty()) throw std::invalid_argument(misfit);
  if (cloud.size() > options_.max_points)
    throw std::length_error(
        "cloud has " + std::to_string(cloud.size()) + " points, more than the " +
        std::to_string(options_.max_points) + " this segmenter takes (profile '" + sensor_.name +
        "', " + std::to_string(sensor_.beams) + " beams x " + std::to_string(sensor_.width) +
        " columns): wrong --sensor? Raise the limit with --max-points if the sensor really "
        "returns this many");
}

const Frame& Segmenter::Segment(const Cloud& cloud, FrameTimes* times) {
  if (!pending_.empty())
    throw std::logic_error("Segment called with frames pending: Collect them first");
  Submit(cloud);
  return Collect(times);
}

bool Segmenter::CanSubmit() const {
  if (staged_ > 0 || pending_.empty()) return true;  // a batch being filled has room
  const uint32_t blocks = slots_ / batch_;
  const uint32_t first = pending_.front() / batch_, last = pending_.back() / batch_;
  return (last + blocks - first) % blocks + 1 < blocks;  // blocks with frames pending
}

void Segmenter::Submit(const Cloud& cloud) { Submit(cloud, false); }

void Segmenter::SubmitBorrowed(const Cloud& cloud) { Submit(cloud, true); }

void Segmenter::Submit(const Cloud& cloud, bool borrowed) {
  if (!CanSubmit())
    throw std::logic_error("Submit called with " + std::to_string(pending_.size()) +
                           " frames pending, the most in flight: Collect first");
  const Cloud* staged = &cloud;
  if (sensor_.pattern != ScanPattern::kSpinning && !cloud.ring.empty()) {
    unringed_.xyzi = cloud.xyzi;  // into the scratch's vector: no allocation once it has grown
    unringed_.ring.clear();
    staged = &unringed_;
    borrowed = false;  // the scratch is the next cloud's too
  }
  CheckCloud(*staged);
  if (staged_ == 0) next_slot_ = next_block_ * batch_;
  const uint32_t slot = next_slot_;
  slot_mounts_[slot] = FrameMount(*staged, sensor_, params_);
  pipeline_->Stage(slot, *staged, slot_mounts_[slot].mount, borrowed);
  ++staged_;
  pending_.push_back(slot);
  next_slot_ = slot + 1;
  if (staged_ == batch_) SubmitStaged();
}

void Segmenter::SubmitStaged() {
  const uint32_t first = pending_.back() + 1 - staged_;  // a batch fills its block from the start
  const uint32_t count = staged_;
  staged_ = 0;
  next_block_ = (first / batch_ + 1) % (slots_ / batch_);
  pipeline_->SubmitStaged(first, count);
}

const Frame& Segmenter::Collect(FrameTimes* times) {
  if (pending_.empty()) throw std::logic_error("Collect called with no frame pending");
  if (staged_ == pending_.size()) SubmitStaged();  // the oldest frame waits in a partial batch
  const uint32_t slot = pending_.front();
  pending_.pop_front();
  pipeline_->Collect(slot, frame_, options_.all_buffers, times);
  mount_ = slot_mounts_[slot];
  return frame_;
}

}  // namespace lpir
