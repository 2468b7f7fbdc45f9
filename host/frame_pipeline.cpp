// The frame pipeline: buffers, stages and the recording of one frame.
#include "host/frame_pipeline.h"

#include <cassert>
#include <cstdio>
#include <cstring>
#include <string>

#include "host/stages/back_project.h"
#include "host/stages/classify_pixels.h"
#include "host/stages/coarse_segment.h"
#include "host/stages/feature_maps.h"
#include "host/stages/fuse.h"
#include "host/stages/grid_reduce.h"
#include "host/stages/grow.h"
#include "host/stages/prepare.h"
#include "host/stages/project.h"
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

struct FramePipeline::TableBuffers {
  Buffer column_dir, beam_bound, beam_origin, ring_bound2, ring_inner;
};

struct FramePipeline::Buffers {
  Buffer params, points, ring;
  Buffer flags, zt, r2, inten;                                // 1 prepare
  Buffer point_pixel, pixel_key, pixel_point, project_exact;  // 2 project
  Buffer point_cell, cell_zmin, cell_zmax, cell_count;        // 3 grid reduce
  Buffer cell_seed_mode, cell_plane, coarse, coarse_scratch;  // 4 coarse segment
  Buffer pixel_filled, f_range, f_inten, f_height, f_slope, f_edge_l, f_edge_r, f_varz, f_vari,
      feature_pack;                                                     // 5 feature maps
  Buffer pixel_class, pixel_fused;                                      // 6 classify, 7 fuse
  Buffer pixel_grown, pixel_comp, pixel_label, grow_reach, grow_sizes;  // 8 grow
  Buffer label_why;                                                     // 9 back-project
};

struct FramePipeline::Stages {
  PrepareStage prepare;
  ProjectStage project;
  GridReduceStage grid_reduce;
  CoarseSegmentStage coarse_segment;
  FeatureMapsStage feature_maps;
  ClassifyPixelsStage classify_pixels;
  FuseStage fuse;
  GrowStage grow;
  BackProjectStage back_project;
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

// The nine stages bound to one slot's buffers and the shared tables.
Result<std::unique_ptr<FramePipeline::Stages>> FramePipeline::MakeStages(const Device& device,
                                                                         const TableBuffers& t,
                                                                         Buffers& b) {
  PrepareBuffers prepare{&b.params, &b.points, &b.ring, &b.flags, &b.zt, &b.r2, &b.inten};
  ProjectBuffers project{&b.params,      &b.points,     &b.ring,        &b.flags,
                         &b.r2,          &t.column_dir, &t.beam_bound,  &t.beam_origin,
                         &b.point_pixel, &b.pixel_key,  &b.pixel_point, &b.project_exact};
  GridReduceBuffers grid{&b.params,      &b.flags,      &b.r2,        &b.zt,        &b.point_pixel,
                         &t.ring_bound2, &b.point_cell, &b.cell_zmin, &b.cell_zmax, &b.cell_count};
  CoarseSegmentBuffers coarse{&b.params,         &b.points,     &b.zt,         &b.point_cell,
                              &b.cell_zmin,      &b.cell_zmax,  &b.cell_count, &t.ring_inner,
                              &b.cell_seed_mode, &b.cell_plane, &b.coarse,     &b.coarse_scratch};
  FeatureMapsBuffers features{&b.params,   &b.pixel_point,  &b.r2,          &b.zt,
                              &b.inten,    &b.pixel_filled, &b.f_range,     &b.f_inten,
                              &b.f_height, &b.f_slope,      &b.f_edge_l,    &b.f_edge_r,
                              &b.f_varz,   &b.f_vari,       &b.feature_pack};
  ClassifyPixelsBuffers classify{&b.params,  &b.pixel_filled, &b.f_edge_l, &b.f_edge_r,
                                 &b.f_slope, &b.f_varz,       &b.f_vari,   &b.pixel_class};
  FuseBuffers fuse{&b.params,       &b.pixel_class, &b.pixel_point, &b.coarse,
                   &b.pixel_filled, &b.f_range,     &b.f_height,    &b.pixel_fused};
  GrowBuffers grow{&b.params,      &b.pixel_fused, &b.f_inten,     &b.f_height,   &b.f_range,
                   &b.pixel_grown, &b.pixel_comp,  &b.pixel_label, &b.grow_reach, &b.grow_sizes};
  BackProjectBuffers back{&b.params,      &b.flags,   &b.point_pixel, &b.pixel_point,
                          &b.pixel_label, &b.f_range, &b.f_height,    &b.r2,
                          &b.zt,          &b.coarse,  &b.label_why};
  LPIR_VK_ASSIGN_OR_RETURN(PrepareStage s1, PrepareStage::Create(device, prepare));
  LPIR_VK_ASSIGN_OR_RETURN(ProjectStage s2, ProjectStage::Create(device, project));
  LPIR_VK_ASSIGN_OR_RETURN(GridReduceStage s3, GridReduceStage::Create(device, grid));
  LPIR_VK_ASSIGN_OR_RETURN(CoarseSegmentStage s4, CoarseSegmentStage::Create(device, coarse));
  LPIR_VK_ASSIGN_OR_RETURN(FeatureMapsStage s5, FeatureMapsStage::Create(device, features));
  LPIR_VK_ASSIGN_OR_RETURN(ClassifyPixelsStage s6, ClassifyPixelsStage::Create(device, classify));
  LPIR_VK_ASSIGN_OR_RETURN(FuseStage s7, FuseStage::Create(device, fuse));
  LPIR_VK_ASSIGN_OR_RETURN(GrowStage s8, GrowStage::Create(device, grow));
  LPIR_VK_ASSIGN_OR_RETURN(BackProjectStage s9, BackProjectStage::Create(device, back));
  return std::unique_ptr<Stages>(new Stages{std::move(s1), std::move(s2), std::move(s3),
                                            std::move(s4), std::move(s5), std::move(s6),
                                            std::move(s7), std::move(s8), std::move(s9)});
}

Result<FramePipeline> FramePipeline::Create(const Context& context, const Params& params,
                                            const Tables& tables, uint32_t max_points,
                                            uint32_t slots, const DeviceLimits* limits) {
  const Device& device = context.device();
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

  FramePipeline fp;
  fp.context_ = &context;
  fp.params_ = params;
  fp.max_points_ = max_points;
  fp.cells_ = cells;
  fp.pixels_ = uint32_t(pixels);
  fp.tables_ = std::make_unique<TableBuffers>();
  TableBuffers& t = *fp.tables_;
  Buffers b;  // the sizes below, and their names in the limit errors, are those of every slot's
  const VkDeviceSize point = 4 * VkDeviceSize(max_points), pixel = 4 * pixels, cell = 4 * cells;
  // Each slot's staging: the points (16 bytes each) and rings (4 each) up, label_why down.
  const VkDeviceSize upload_bytes = 5 * point;
  const VkDeviceSize download_bytes = BackProjectStage::LabelWhyBytes(max_points);
  auto make = [&](Buffer& buffer, VkDeviceSize bytes) -> Status {
    LPIR_VK_ASSIGN_OR_RETURN(buffer, Buffer::Create(device, bytes, MemoryKind::kDeviceLocal));
    fp.device_bytes_ += buffer.size();
    return Status();
  };
  auto table = [&](Buffer& buffer, const std::vector<float>& values) -> Status {
    return make(buffer, 4 * VkDeviceSize(values.size()));
  };
  struct Sized {
    Buffer* buffer;
    VkDeviceSize bytes;
  };
  // Every frame buffer of a slot and its size.
  auto sizes_of = [&](Buffers& x) {
    return std::vector<Sized>{{&x.params, sizeof(Params)},
                              {&x.points, 4 * point},
                              {&x.ring, point},
                              {&x.flags, point},
                              {&x.zt, point},
                              {&x.r2, point},
                              {&x.inten, point},
                              {&x.point_pixel, point},
                              {&x.pixel_key, pixel},
                              {&x.pixel_point, pixel},
                              {&x.point_cell, point},
                              {&x.cell_zmin, cell},
                              {&x.project_exact, ProjectStage::ExactListBytes(max_points)},
                              {&x.cell_zmax, cell},
                              {&x.cell_count, cell},
                              {&x.cell_seed_mode, cell},
                              {&x.cell_plane, 8 * cell},
                              {&x.coarse, point},
                              {&x.coarse_scratch, CoarseSegmentStage::ScratchBytes(cells)},
                              {&x.pixel_filled, pixel},
                              {&x.f_range, pixel},
                              {&x.f_inten, pixel},
                              {&x.f_height, pixel},
                              {&x.f_slope, pixel},
                              {&x.f_edge_l, pixel},
                              {&x.f_edge_r, pixel},
                              {&x.f_varz, pixel},
                              {&x.f_vari, pixel},
                              {&x.feature_pack, FeatureMapsStage::PackBytes(pixels)},
                              {&x.pixel_class, pixel},
                              {&x.pixel_fused, pixel},
                              {&x.pixel_grown, pixel},
                              {&x.pixel_comp, pixel},
                              {&x.pixel_label, pixel},
                              {&x.grow_reach, GrowStage::ReachBytes(pixels)},
                              {&x.grow_sizes, pixel},
                              {&x.label_why, BackProjectStage::LabelWhyBytes(max_points)}};
  };
  const std::vector<Sized> sizes = sizes_of(b);
  {
    // The device's limits, before anything is allocated: every storage buffer's size (what it
    // scales with named in the error), Params, and the sum of all against the heap.
    const DeviceLimits device_limits = limits ? *limits : DeviceLimits::Of(device);
    const std::string points_need = "max_points " + std::to_string(max_points);
    const std::string pixels_need = "an image of " + std::to_string(params.beams) + " x " +
                                    std::to_string(params.width) + " pixels";
    const std::string cells_need = "a grid of " + std::to_string(cells) + " cells";
    const struct {
      const Buffer* buffer;
      const char* name;
      const std::string* need;
    } names[] = {{&b.points, "points", &points_need},
                 {&b.ring, "ring", &points_need},
                 {&b.flags, "flags", &points_need},
                 {&b.zt, "zt", &points_need},
                 {&b.r2, "r2", &points_need},
                 {&b.inten, "inten", &points_need},
                 {&b.point_pixel, "point_pixel", &points_need},
                 {&b.project_exact, "project_exact", &points_need},
                 {&b.point_cell, "point_cell", &points_need},
                 {&b.coarse, "coarse", &points_need},
                 {&b.label_why, "label_why", &points_need},
                 {&b.pixel_key, "pixel_key", &pixels_need},
                 {&b.pixel_point, "pixel_point", &pixels_need},
                 {&b.feature_pack, "feature_pack", &pixels_need},
                 {&b.grow_reach, "grow_reach", &pixels_need},
                 {&b.cell_plane, "cell_plane", &cells_need},
                 {&b.coarse_scratch, "coarse_scratch", &cells_need}};
    const std::string other_need = points_need + " and " + pixels_need;
    uint64_t total = 0;
    for (const auto& s : sizes) {
      total += s.bytes;
      if (s.buffer == &b.params) {
        if (s.bytes > device_limits.max_uniform_buffer_range)
          return PipelineError("the parameters need a " + std::to_string(s.bytes) +
                               "-byte uniform buffer; this device's maxUniformBufferRange is " +
                               std::to_string(device_limits.max_uniform_buffer_range));
        continue;
      }
      if (s.bytes <= device_limits.max_storage_buffer_range) continue;
      const char* name = "device";
      const std::string* need = &other_need;
      for (const auto& n : names)
        if (n.buffer == s.buffer) name = n.name, need = n.need;
      return PipelineError(*need + " needs a " + BytesText(s.bytes) + " (" +
                           std::to_string(s.bytes) + " bytes) " + name +
                           " buffer; this device's maxStorageBufferRange is " +
                           std::to_string(device_limits.max_storage_buffer_range));
    }
    total *= slots;  // every slot owns its frame buffers; the tables are shared
    const std::vector<float>* table_values[] = {&tables.column_dir, &tables.beam_bound,
                                                &tables.beam_origin, &tables.ring_bound2,
                                                &tables.ring_inner};
    for (const std::vector<float>* values : table_values) {
      const uint64_t bytes = 4 * uint64_t(values->size());
      total += bytes;
      if (bytes > device_limits.max_storage_buffer_range)
        return PipelineError(pixels_need + " and " + cells_need + " need a " + BytesText(bytes) +
                             " table; this device's maxStorageBufferRange is " +
                             std::to_string(device_limits.max_storage_buffer_range));
    }
    const uint64_t staging = uint64_t(slots) * (upload_bytes + download_bytes);
    if (device_limits.staging_in_device_heap) total += staging;
    if (total > device_limits.device_local_heap)
      return PipelineError(points_need + " and " + pixels_need + " need " + BytesText(total) +
                           " (" + std::to_string(total) + " bytes) of device memory" +
                           (device_limits.staging_in_device_heap
                                ? " (" + std::to_string(slots) + " staging slots included)"
                                : std::string()) +
                           "; this device's device-local memory heap holds " +
                           std::to_string(device_limits.device_local_heap) + " bytes");
  }
  LPIR_VK_RETURN_IF_ERROR(table(t.column_dir, tables.column_dir));
  LPIR_VK_RETURN_IF_ERROR(table(t.beam_bound, tables.beam_bound));
  LPIR_VK_RETURN_IF_ERROR(table(t.beam_origin, tables.beam_origin));
  LPIR_VK_RETURN_IF_ERROR(table(t.ring_bound2, tables.ring_bound2));
  LPIR_VK_RETURN_IF_ERROR(table(t.ring_inner, tables.ring_inner));
  {
    LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
    const struct {
      const Buffer* buffer;
      const std::vector<float>* values;
    } uploads[] = {{&t.column_dir, &tables.column_dir},
                   {&t.beam_bound, &tables.beam_bound},
                   {&t.beam_origin, &tables.beam_origin},
                   {&t.ring_bound2, &tables.ring_bound2},
                   {&t.ring_inner, &tables.ring_inner}};
    for (const auto& u : uploads)
      if (!u.values->empty())
        LPIR_VK_RETURN_IF_ERROR(transfer.Upload(*u.buffer, u.values->data(), 4 * u.values->size()));
  }

  const bool timed = device.timestamp_valid_bits() != 0;
  for (uint32_t i = 0; i < slots; ++i) {
    LPIR_VK_ASSIGN_OR_RETURN(CommandBuffer cmd, CommandBuffer::Create(device));
    LPIR_VK_ASSIGN_OR_RETURN(Fence fence, Fence::Create(device));
    LPIR_VK_ASSIGN_OR_RETURN(Buffer upload,
                             Buffer::Create(device, upload_bytes, MemoryKind::kHostVisible));
    LPIR_VK_ASSIGN_OR_RETURN(Buffer download,
                             Buffer::Create(device, download_bytes, MemoryKind::kHostVisible));
    fp.device_bytes_ += upload.size() + download.size();
    Slot slot{std::move(cmd), std::move(fence), std::move(upload), std::move(download), {}, {}, {}};
    slot.buffers = std::make_unique<Buffers>();
    for (const Sized& own : sizes_of(*slot.buffers))
      LPIR_VK_RETURN_IF_ERROR(make(*own.buffer, own.bytes));
    LPIR_VK_ASSIGN_OR_RETURN(slot.stages, MakeStages(device, t, *slot.buffers));
    if (timed) {
      LPIR_VK_ASSIGN_OR_RETURN(TimestampQueries q, TimestampQueries::Create(device, kQueries));
      slot.queries.push_back(std::move(q));
    }
    fp.slots_.push_back(std::move(slot));
  }
  // The largest frame's dispatches, recorded once and never submitted (Record begins the
  // command buffer anew every frame): a stage over more workgroups than the device dispatches
  // fails here, naming maxComputeWorkGroupCount[0].
  {
    Slot& first = fp.slots_.front();
    first.n = max_points;
    first.has_ring = true;
    Status status = first.cmd.Begin();
    if (status.ok()) status = fp.RecordFrame(first, first.cmd);
    if (status.ok()) status = first.cmd.End();
    first.n = 0;
    first.has_ring = false;
    if (!status.ok())
      return PipelineError("max_points " + std::to_string(max_points) + ": " + status.message());
  }
  return fp;
}

Status FramePipeline::Submit(uint32_t slot, const Cloud& cloud) {
  LPIR_VK_RETURN_IF_ERROR(Stage(slot, cloud));
  return SubmitStaged(slot, 1);
}

Status FramePipeline::Stage(uint32_t index, const Cloud& cloud) {
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
  Buffers& b = *slot.buffers;
  Stages& s = *slot.stages;
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
  Params params = params_;
  params.has_ring = has_ring ? 1u : 0u;
  cmd.UpdateBuffer(b.params, &params, sizeof(Params));
  if (n) cmd.CopyBuffer(slot.upload, b.points, 16 * VkDeviceSize(n));
  if (n && has_ring) cmd.CopyBuffer(slot.upload, b.ring, 4 * VkDeviceSize(n), 4 * point);
  cmd.TransferToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.prepare.Record(cmd, n));
  cmd.ComputeToCompute();
  time();
  // Project starts with fills (transfer writes) of its pixel buffers, which nothing of this
  // frame has touched yet; the head barrier ordered them after the slot's previous frame.
  LPIR_VK_RETURN_IF_ERROR(s.project.Record(cmd, n));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.grid_reduce.Record(cmd, n, cells_));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.coarse_segment.Record(cmd, n, cells_));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.feature_maps.Record(cmd, params_.width, params_.beams));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.classify_pixels.Record(cmd, pixels_));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.fuse.Record(cmd, params_.width, params_.beams));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.grow.Record(cmd, params_.width, params_.beams));
  cmd.ComputeToCompute();
  time();
  LPIR_VK_RETURN_IF_ERROR(s.back_project.Record(cmd, n));
  cmd.ComputeToTransfer();
  time();
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

  if (times) {
    *times = FrameTimes{};
    times->upload_ms = times->download_ms = times->total_ms = -1;
    for (double& ms : times->stage_ms) ms = -1;
    if (!slot.queries.empty()) {
      double ns[kQueries];
      LPIR_VK_RETURN_IF_ERROR(slot.queries[0].Read(ns));
      times->upload_ms = (ns[1] - ns[0]) / 1e6;
      for (int k = 0; k < kStageCount; ++k) times->stage_ms[k] = (ns[k + 2] - ns[k + 1]) / 1e6;
      const uint32_t last = kQueries - 1;  // after the download
      times->download_ms = (ns[last] - ns[last - 1]) / 1e6;
      times->total_ms = (ns[last] - ns[0]) / 1e6;
    }
  }

  if (all_buffers) {
    const Buffers& b = *slot.buffers;
    LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(context_->device()));
    Status status;
    auto read = [&](const Buffer& src, auto& dst, size_t count) {
      dst.resize(count);
      if (status.ok() && count) status = transfer.Download(src, dst.data(), count * sizeof(dst[0]));
    };
    const size_t px = pixels_, cells = cells_;
    read(b.flags, out.flags, n);
    read(b.zt, out.zt, n);
    read(b.r2, out.r2, n);
    read(b.inten, out.inten, n);
    read(b.point_pixel, out.point_pixel, n);
    read(b.pixel_key, out.pixel_key, px);
    read(b.pixel_point, out.pixel_point, px);
    read(b.point_cell, out.point_cell, n);
    read(b.cell_zmin, out.cell_zmin, cells);
    read(b.cell_zmax, out.cell_zmax, cells);
    read(b.cell_count, out.cell_count, cells);
    read(b.cell_seed_mode, out.cell_seed_mode, cells);
    read(b.cell_plane, out.cell_plane, 8 * cells);
    read(b.coarse, out.coarse, n);
    read(b.pixel_filled, out.pixel_filled, px);
    read(b.f_range, out.f_range, px);
    read(b.f_inten, out.f_inten, px);
    read(b.f_height, out.f_height, px);
    read(b.f_slope, out.f_slope, px);
    read(b.f_edge_l, out.f_edge_l, px);
    read(b.f_edge_r, out.f_edge_r, px);
    read(b.f_varz, out.f_varz, px);
    read(b.f_vari, out.f_vari, px);
    read(b.pixel_class, out.pixel_class, px);
    read(b.pixel_fused, out.pixel_fused, px);
    read(b.pixel_grown, out.pixel_grown, px);
    read(b.pixel_comp, out.pixel_comp, px);
    read(b.pixel_label, out.pixel_label, px);
    LPIR_VK_RETURN_IF_ERROR(status);
  }
  return Status();
}

}  // namespace lpir::vk
