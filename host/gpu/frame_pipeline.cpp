// The frame pipeline: buffers, stages and the recording of one frame, all made from the stage
// table (reference_cpu/stage_table.def).
#include "host/gpu/frame_pipeline.h"

#include <cassert>
#include <cstdio>
#include <cstring>
#include <string>

#include "host/gpu/stage_headers.h"  // generated: every stage's host/gpu/<name>.h
#include "host/vk/transfer.h"

namespace lpir::vk {
namespace {

Error PipelineError(const std::string& message) { return UsageError("frame pipeline", message); }

// "1.6 GB", "80.0 MB", "4.1 kB" (decimal units, one decimal), "12 bytes".
std::string BytesText(uint64_t bytes) {
  const struct {
    double unit;
    const char* name;
  } units[] = {{1e9, "GB"}, {1e6, "MB"}, {1e3, "kB"}};
  for (const auto& u : units)
    if (double(bytes) >= u.unit) {
      char text[32];
      std::snprintf(text, sizeof(text), "%.1f %s", double(bytes) / u.unit, u.name);
      return text;
    }
  return std::to_string(bytes) + " bytes";
}

// Each slot's staging: the points (16 bytes each) and rings (4 each) up, label_why down.
VkDeviceSize UploadBytes(uint32_t max_points) { return 20 * VkDeviceSize(max_points); }
VkDeviceSize DownloadBytes(uint32_t max_points) {
  return BackProjectStage::LabelWhyBytes(max_points);
}

// Bytes of a device buffer of `elements` elements of `size` bytes: whole 32-bit words.
VkDeviceSize DeviceBytes(uint64_t elements, size_t size) {
  return (VkDeviceSize(elements) * size + 3) / 4 * 4;
}

// One storage buffer of a slot: where it is, its name, what it scales with and its bytes.
struct Sized {
  Buffer* buffer;
  const char* name;
  Per per;
  VkDeviceSize bytes;
};

// Every storage buffer of a slot (all but Params), in table order, sized for max_points points.
std::vector<Sized> SizesOf(FrameBuffers& b, const Params& p, uint32_t max_points) {
  auto items = [&](Per per) { return ItemsOf(per, max_points, p); };
  return {
      {&b.points, "points", Per::kPoint, DeviceBytes(items(Per::kPoint), 16)},
      {&b.ring, "ring", Per::kPoint, DeviceBytes(items(Per::kPoint), 4)},
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(stage, name, type, per, stride) \
  {&b.name, #name, Per::per, DeviceBytes(items(Per::per) * stride, sizeof(type))},
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH(stage, name, type, per, stride, extra) \
  {&b.name, #name, Per::per, DeviceBytes(items(Per::per) * stride + extra, sizeof(type))},
#include "reference_cpu/stage_table.def"
  };
}

// What a buffer of `per` items scales with, as the limit errors name it.
std::string NeedOf(Per per, const Params& p, uint32_t max_points) {
  switch (per) {
    case Per::kPoint:
      return "max_points " + std::to_string(max_points);
    case Per::kPixel:
      return "an image of " + std::to_string(p.beams) + " x " + std::to_string(p.width) + " pixels";
    case Per::kCell:
      break;
  }
  return "a grid of " + std::to_string(CellCount(p)) + " cells";
}

// The arguments Create refuses before looking at the device.
Status CheckArguments(const Params& params, const Tables& tables, uint32_t max_points,
                      uint32_t slots) {
  if (max_points == 0 || max_points > UINT32_MAX / 16)
    return PipelineError("max_points must be between 1 and " + std::to_string(UINT32_MAX / 16));
  if (slots == 0) return PipelineError("at least one frame slot is needed");
  const uint64_t pixels = uint64_t(params.width) * params.beams;
  const uint32_t cells = CellCount(params), rings = params.rings_near + params.rings_far;
  if (pixels == 0 || pixels > UINT32_MAX / 32 || cells == 0)
    return PipelineError("an image of " + std::to_string(pixels) + " pixels and a grid of " +
                         std::to_string(cells) + " cells");
  if (tables.column_dir.size() != 2 * size_t(params.width) ||
      tables.beam_bound.size() + 1 != params.beams ||
      tables.beam_origin.size() + 1 != params.beams || tables.ring_bound2.size() != rings ||
      tables.ring_inner.size() != rings)
    return PipelineError("the tables do not match the parameters (see MakeTables)");
  return Status();
}

// The tables' device buffers, each with its values.
struct TableValues {
  Buffer* buffer;
  const std::vector<float>* values;
};
std::vector<TableValues> TablesOf(TableBuffers& t, const Tables& tables) {
  return {{&t.column_dir, &tables.column_dir},
          {&t.beam_bound, &tables.beam_bound},
          {&t.beam_origin, &tables.beam_origin},
          {&t.ring_bound2, &tables.ring_bound2},
          {&t.ring_inner, &tables.ring_inner}};
}

// Params against maxUniformBufferRange, every storage buffer and table against
// maxStorageBufferRange. Returns the device-local bytes of them all: the tables once, the frame
// buffers once a slot, and the staging buffers once a slot when they share the heap.
Result<uint64_t> CheckRanges(const std::vector<Sized>& sizes, const Params& params,
                             const Tables& tables, uint32_t max_points, uint32_t slots,
                             const DeviceLimits& limits) {
  const uint64_t storage = limits.max_storage_buffer_range;
  if (sizeof(Params) > limits.max_uniform_buffer_range)
    return PipelineError("the parameters need a " + std::to_string(sizeof(Params)) +
                         "-byte uniform buffer; this device's maxUniformBufferRange is " +
                         std::to_string(limits.max_uniform_buffer_range));
  uint64_t total = sizeof(Params);
  for (const Sized& s : sizes) {
    total += s.bytes;
    if (s.bytes > storage)
      return PipelineError(NeedOf(s.per, params, max_points) + " needs a " + BytesText(s.bytes) +
                           " (" + std::to_string(s.bytes) + " bytes) " + s.name +
                           " buffer; this device's maxStorageBufferRange is " +
                           std::to_string(storage));
  }
  total *= slots;  // every slot owns its frame buffers; the tables are shared
  for (const std::vector<float>* values :
       {&tables.column_dir, &tables.beam_bound, &tables.beam_origin, &tables.ring_bound2,
        &tables.ring_inner}) {
    const uint64_t bytes = 4 * uint64_t(values->size());
    total += bytes;
    if (bytes > storage)
      return PipelineError(NeedOf(Per::kPixel, params, max_points) + " and " +
                           NeedOf(Per::kCell, params, max_points) + " need a " + BytesText(bytes) +
                           " table; this device's maxStorageBufferRange is " +
                           std::to_string(storage));
  }
  if (limits.staging_in_device_heap)
    total += uint64_t(slots) * (UploadBytes(max_points) + DownloadBytes(max_points));
  return total;
}

// The sum of every buffer against the device-local heap.
Status CheckHeap(uint64_t total, const Params& params, uint32_t max_points, uint32_t slots,
                 const DeviceLimits& limits) {
  if (total <= limits.device_local_heap) return Status();
  return PipelineError(
      NeedOf(Per::kPoint, params, max_points) + " and " + NeedOf(Per::kPixel, params, max_points) +
      " need " + BytesText(total) + " (" + std::to_string(total) + " bytes) of device memory" +
      (limits.staging_in_device_heap ? " (" + std::to_string(slots) + " staging slots included)"
                                     : std::string()) +
      "; this device's device-local memory heap holds " + std::to_string(limits.device_local_heap) +
      " bytes");
}

}  // namespace

DeviceLimits DeviceLimits::Of(const Device& device) {
  DeviceLimits limits;
  limits.max_storage_buffer_range = device.limits().maxStorageBufferRange;
  limits.max_uniform_buffer_range = device.limits().maxUniformBufferRange;
  // The heaps of the memory types Buffer::Create takes (every type allowed: a buffer's own
  // memoryTypeBits are only known once it exists).
  const VkPhysicalDeviceMemoryProperties& memory = device.memory_properties();
  const Result<uint32_t> local = device.FindMemoryType(~0u, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
  const Result<uint32_t> host = device.FindMemoryType(
      ~0u, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
      VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
  if (local.ok()) {
    const uint32_t heap = memory.memoryTypes[local.value()].heapIndex;
    limits.device_local_heap = memory.memoryHeaps[heap].size;
    limits.staging_in_device_heap = host.ok() && memory.memoryTypes[host.value()].heapIndex == heap;
  }
  return limits;
}

struct FramePipeline::Stages {
#define LPIR_STAGE(name, Type, parameters) Type##Stage name;
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
};

// Frames still in flight are waited for: their command buffers use what is about to be freed.
void FramePipeline::WaitForAll() {
  for (Slot& slot : slots_) {
    if (slot.fence_pending) (void)slot.fence.WaitAndReset();  // a lost device: nothing to wait
    slot.fence_pending = false;
    slot.busy = false;
    slot.frames = 0;
  }
}

FramePipeline::~FramePipeline() { WaitForAll(); }
FramePipeline::FramePipeline(FramePipeline&&) noexcept = default;
FramePipeline& FramePipeline::operator=(FramePipeline&& other) noexcept {
  if (this != &other) {
    WaitForAll();
    context_ = other.context_;
    params_ = other.params_;
    max_points_ = other.max_points_, cells_ = other.cells_, pixels_ = other.pixels_;
    device_bytes_ = other.device_bytes_;
    last_counts_ = other.last_counts_;
    // The slots (their stages and buffers) before the tables their stages point into.
    slots_ = std::move(other.slots_);
    tables_ = std::move(other.tables_);
  }
  return *this;
}

// Every stage bound to one slot's buffers (and through them the shared tables).
Result<std::unique_ptr<FramePipeline::Stages>> FramePipeline::MakeStages(const Device& device,
                                                                         const FrameBuffers& b) {
#define LPIR_STAGE(name, Type, parameters)                   \
  Result<Type##Stage> name = Type##Stage::Create(device, b); \
  if (!name.ok()) return name.error();
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  return std::unique_ptr<Stages>(new Stages{
#define LPIR_STAGE(name, Type, parameters) std::move(name).value(),
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  });
}

// Calls fn(stage) for every stage of `s` in run order; stops at the first error.
template <typename Fn>
Status FramePipeline::ForEachStage(const Stages& s, Fn&& fn) {
#define LPIR_STAGE(name, Type, parameters) LPIR_VK_RETURN_IF_ERROR(fn(s.name));
#define LPIR_BUFFER LPIR_IGNORE
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  return Status();
}

Result<FramePipeline> FramePipeline::Create(const Context& context, const Params& params,
                                            const Tables& tables, uint32_t max_points,
                                            uint32_t slots, const DeviceLimits* limits) {
  LPIR_VK_RETURN_IF_ERROR(CheckArguments(params, tables, max_points, slots));
  const Device& device = context.device();
  {
    // The device's limits, before anything is allocated (the sizes are every slot's).
    const DeviceLimits device_limits = limits ? *limits : DeviceLimits::Of(device);
    FrameBuffers sizing;
    LPIR_VK_ASSIGN_OR_RETURN(const uint64_t total,
                             CheckRanges(SizesOf(sizing, params, max_points), params, tables,
                                         max_points, slots, device_limits));
    LPIR_VK_RETURN_IF_ERROR(CheckHeap(total, params, max_points, slots, device_limits));
  }
  FramePipeline fp;
  fp.context_ = &context;
  fp.params_ = params;
  fp.max_points_ = max_points;
  fp.cells_ = CellCount(params);
  fp.pixels_ = params.width * params.beams;
  LPIR_VK_RETURN_IF_ERROR(fp.MakeTables(tables));
  for (uint32_t i = 0; i < slots; ++i) LPIR_VK_RETURN_IF_ERROR(fp.AddSlot());
  LPIR_VK_RETURN_IF_ERROR(fp.RecordLargestFrame());
  return fp;
}

Status FramePipeline::Allocate(Buffer& buffer, VkDeviceSize bytes, MemoryKind kind) {
  LPIR_VK_ASSIGN_OR_RETURN(buffer, Buffer::Create(context_->device(), bytes, kind));
  device_bytes_ += buffer.size();
  return Status();
}

Status FramePipeline::MakeTables(const Tables& tables) {
  tables_ = std::make_unique<TableBuffers>();
  const std::vector<TableValues> all = TablesOf(*tables_, tables);
  for (const TableValues& t : all)
    LPIR_VK_RETURN_IF_ERROR(Allocate(*t.buffer, 4 * VkDeviceSize(t.values->size())));
  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(context_->device()));
  for (const TableValues& t : all)
    if (!t.values->empty())
      LPIR_VK_RETURN_IF_ERROR(transfer.Upload(*t.buffer, t.values->data(), 4 * t.values->size()));
  return Status();
}

Status FramePipeline::AddSlot() {
  const Device& device = context_->device();
  LPIR_VK_ASSIGN_OR_RETURN(CommandBuffer cmd, CommandBuffer::Create(device));
  LPIR_VK_ASSIGN_OR_RETURN(Fence fence, Fence::Create(device));
  Slot slot{std::move(cmd), std::move(fence), {}, {}, {}, {}, {}};
  slot.mount = MountOf(params_);
  LPIR_VK_RETURN_IF_ERROR(
      Allocate(slot.upload, UploadBytes(max_points_), MemoryKind::kHostVisible));
  LPIR_VK_RETURN_IF_ERROR(
      Allocate(slot.download, DownloadBytes(max_points_), MemoryKind::kHostVisible));
  slot.buffers = std::make_unique<FrameBuffers>();
  FrameBuffers& b = *slot.buffers;
  b.tables = tables_.get();
  LPIR_VK_RETURN_IF_ERROR(Allocate(b.params, sizeof(Params)));
  for (const Sized& s : SizesOf(b, params_, max_points_))
    LPIR_VK_RETURN_IF_ERROR(Allocate(*s.buffer, s.bytes));
  LPIR_VK_ASSIGN_OR_RETURN(slot.stages, MakeStages(device, b));
  if (device.timestamp_valid_bits() != 0) {
    LPIR_VK_ASSIGN_OR_RETURN(TimestampQueries q, TimestampQueries::Create(device, kQueries));
    slot.queries.push_back(std::move(q));
  }
  slots_.push_back(std::move(slot));
  return Status();
}

// The largest frame's dispatches, recorded once and never submitted (Record begins the command
// buffer anew every frame): a stage over more workgroups than the device dispatches fails here,
// naming maxComputeWorkGroupCount[0].
Status FramePipeline::RecordLargestFrame() {
  Slot& first = slots_.front();
  first.n = max_points_;
  first.has_ring = true;
  first.mount = MountOf(params_);
  Status status = first.cmd.Begin();
  if (status.ok()) status = RecordFrame(first, first.cmd);
  if (status.ok()) status = first.cmd.End();
  first.n = 0;
  first.has_ring = false;
  if (!status.ok())
    return PipelineError("max_points " + std::to_string(max_points_) + ": " + status.message());
  return Status();
}

Status FramePipeline::Submit(uint32_t slot, const Cloud& cloud) {
  LPIR_VK_RETURN_IF_ERROR(Stage(slot, cloud));
  return SubmitStaged(slot, 1);
}

Status FramePipeline::Stage(uint32_t index, const Cloud& cloud, const Mount& mount) {
  if (index >= slots_.size() || slots_[index].busy || slots_[index].staged || slots_[index].frames)
    return PipelineError("slot " + std::to_string(index) + " is not free");
  const uint64_t n = cloud.size();
  const bool has_ring = !cloud.ring.empty();
  assert(n <= max_points_ && (!has_ring || cloud.ring.size() == n));  // checked by the caller
  Slot& slot = slots_[index];
  auto* upload = static_cast<char*>(slot.upload.mapped());
  if (n) std::memcpy(upload, cloud.xyzi.data(), 16 * n);
  if (has_ring && n) std::memcpy(upload + 16 * VkDeviceSize(max_points_), cloud.ring.data(), 4 * n);
  slot.n = uint32_t(n);
  slot.has_ring = has_ring;
  slot.mount = mount;
  slot.staged = true;
  return Status();
}

Status FramePipeline::SubmitStaged(uint32_t first, uint32_t count) {
  if (count == 0) return PipelineError("a batch of no frame");
  if (first >= slots_.size() || count > slots_.size() - first)
    return PipelineError("slots " + std::to_string(first) + " .. " +
                         std::to_string(uint64_t(first) + count - 1) + " do not exist (" +
                         std::to_string(slots_.size()) + " slots)");
  for (uint32_t k = first; k < first + count; ++k)
    if (!slots_[k].staged) return PipelineError("slot " + std::to_string(k) + " holds no cloud");
  Slot& lead = slots_[first];
  CommandBuffer& cmd = lead.cmd;
  std::vector<Tape> tapes(count);
  LPIR_VK_RETURN_IF_ERROR(cmd.Begin());
  for (uint32_t k = 0; k < count; ++k) {
    cmd.BeginTape(&tapes[k]);
    const Status recorded = RecordFrame(slots_[first + k], cmd);
    cmd.EndTape();
    LPIR_VK_RETURN_IF_ERROR(recorded);
  }
  LPIR_VK_RETURN_IF_ERROR(cmd.PlayInterleaved(tapes));
  LPIR_VK_RETURN_IF_ERROR(cmd.End());
  last_counts_ = cmd.counts();
  LPIR_VK_RETURN_IF_ERROR(cmd.Submit(lead.fence));
  lead.fence_pending = true;
  lead.frames = count;
  for (uint32_t k = first; k < first + count; ++k) {
    Slot& slot = slots_[k];
    slot.staged = false;
    slot.busy = true;
    slot.lead = first;
  }
  return Status();
}

Status FramePipeline::RecordFrame(Slot& slot, CommandBuffer& cmd) {
  const FrameBuffers& b = *slot.buffers;
  const uint32_t n = slot.n;
  const bool has_ring = slot.has_ring;
  const VkDeviceSize point = 4 * VkDeviceSize(max_points_);
  const TimestampQueries* q = slot.queries.empty() ? nullptr : &slot.queries[0];
  uint32_t stamp = 0;
  auto time = [&] {
    if (q) cmd.WriteTimestamp(*q, stamp++);
  };

  if (q) cmd.ResetQueries(*q);
  time();
  // The slot's previous frame has finished with its buffers (the queue's earlier work is done).
  cmd.ComputeToTransfer();
  Params params = WithMount(params_, slot.mount);
  params.has_ring = has_ring ? 1u : 0u;
  cmd.UpdateBuffer(b.params, &params, sizeof(Params));
  if (n) cmd.CopyBuffer(slot.upload, b.points, 16 * VkDeviceSize(n));
  if (n && has_ring) cmd.CopyBuffer(slot.upload, b.ring, 4 * VkDeviceSize(n), 4 * point);
  cmd.TransferToCompute();
  time();
  // Each stage after a barrier for the one before. A stage may start with fills (transfer
  // writes) of buffers nothing of this frame has touched yet: the head barrier ordered them
  // after the slot's previous frame. The last one's writes go to the download.
  const FrameSize size{n, params_.width, params_.beams, pixels_, cells_};
  int stage = 0;
  LPIR_VK_RETURN_IF_ERROR(ForEachStage(*slot.stages, [&](const auto& s) -> Status {
    LPIR_VK_RETURN_IF_ERROR(s.Record(cmd, size));
    if (++stage < kStageCount)
      cmd.ComputeToCompute();
    else
      cmd.ComputeToTransfer();
    time();
    return Status();
  }));
  if (n) cmd.CopyBuffer(b.label_why, slot.download, BackProjectStage::LabelWhyBytes(n));
  cmd.TransferToHost();
  time();
  return Status();
}

Status FramePipeline::Collect(uint32_t index, Frame& out, bool all_buffers, FrameTimes* times) {
  if (index >= slots_.size() || !slots_[index].busy)
    return PipelineError("slot " + std::to_string(index) + " holds no submitted frame");
  Slot& slot = slots_[index];
  Slot& lead = slots_[slot.lead];
  if (lead.fence_pending) {
    LPIR_VK_RETURN_IF_ERROR(lead.fence.WaitAndReset());
    lead.fence_pending = false;
  }
  slot.busy = false;
  --lead.frames;
  const uint32_t n = slot.n;
  const auto* label_why = static_cast<const uint8_t*>(slot.download.mapped());
  out.n = n;
  out.label_why.assign(label_why, label_why + n);
  out.label.resize(n);
  out.why.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    out.label[i] = LabelOf(label_why[i]);
    out.why[i] = WhyOf(label_why[i]);
  }
  if (times) LPIR_VK_RETURN_IF_ERROR(ReadTimes(slot, *times));
  if (all_buffers) LPIR_VK_RETURN_IF_ERROR(ReadBuffers(slot, out));
  return Status();
}

// The slot's timestamps as times (all -1 without timestamps).
Status FramePipeline::ReadTimes(const Slot& slot, FrameTimes& times) const {
  times = FrameTimes{};
  times.upload_ms = times.download_ms = times.total_ms = -1;
  for (double& ms : times.stage_ms) ms = -1;
  if (slot.queries.empty()) return Status();
  double ns[kQueries];
  LPIR_VK_RETURN_IF_ERROR(slot.queries[0].Read(ns));
  times.upload_ms = (ns[1] - ns[0]) / 1e6;
  for (int k = 0; k < kStageCount; ++k) times.stage_ms[k] = (ns[k + 2] - ns[k + 1]) / 1e6;
  const uint32_t last = kQueries - 1;  // after the download
  times.download_ms = (ns[last] - ns[last - 1]) / 1e6;
  times.total_ms = (ns[last] - ns[0]) / 1e6;
  return Status();
}

// Every table buffer of the slot's frame into `out`, but label_why (the frame's download).
Status FramePipeline::ReadBuffers(const Slot& slot, Frame& out) const {
  const FrameBuffers& b = *slot.buffers;
  LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(context_->device()));
  Status status;
  auto read = [&](const Buffer& src, auto& dst, Per per, uint32_t stride) {
    const void* to = &dst;
    if (to == &out.label_why) return;
    const size_t count = ItemsOf(per, slot.n, params_) * stride;
    dst.resize(count);
    if (status.ok() && count) status = transfer.Download(src, dst.data(), count * sizeof(dst[0]));
  };
#define LPIR_STAGE LPIR_IGNORE
#define LPIR_BUFFER(stage, name, type, per, stride) read(b.name, out.name, Per::per, stride);
#define LPIR_HOST_BUFFER LPIR_IGNORE
#define LPIR_SCRATCH LPIR_IGNORE
#include "reference_cpu/stage_table.def"
  return status;
}

}  // namespace lpir::vk
