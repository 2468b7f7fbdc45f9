// The frame pipeline: buffers, stages and the recording of one frame.
#include "host/frame_pipeline.h"

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
  const Result<uint32_t> local =
      device.FindMemoryType(~0u, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
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

struct FramePipeline::Buffers {
  Buffer params, points, ring;
  Buffer column_dir, beam_bound, beam_origin, ring_bound2, ring_inner;  // tables
  Buffer flags, zt, r2, inten;                                           // 1 prepare
  Buffer point_pixel, pixel_key, pixel_point, project_exact;             // 2 project
  Buffer point_cell, cell_zmin, cell_zmax, cell_count;                   // 3 grid reduce
  Buffer cell_seed_mode, cell_plane, coarse, coarse_scratch;             // 4 coarse segment
  Buffer pixel_filled, f_range, f_inten, f_height, f_slope, f_edge_l, f_edge_r, f_varz,
      f_vari, feature_pack;                                              // 5 feature maps
  Buffer pixel_class, pixel_fused;                                       // 6 classify, 7 fuse
  Buffer pixel_grown, pixel_comp, pixel_label, grow_reach, grow_sizes;  // 8 grow
  Buffer label_why;                                                      // 9 back-project
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
  for (Slot& slot : slots_)
    if (slot.busy) {
      (void)slot.fence.WaitAndReset();  // a lost device has nothing left to wait for
      slot.busy = false;
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
    device_bytes_ = other.device_bytes_, submitted_ = other.submitted_;
    last_counts_ = other.last_counts_;
    // The stages before the buffers they point into.
    stages_ = std::move(other.stages_);
    buffers_ = std::move(other.buffers_);
    slots_ = std::move(other.slots_);
  }
  return *this;
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
  fp.buffers_ = std::make_unique<Buffers>();
  Buffers& b = *fp.buffers_;
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
  const struct {
    Buffer* buffer;
    VkDeviceSize bytes;
  } sizes[] = {
      {&b.params, sizeof(Params)},  {&b.points, 4 * point},      {&b.ring, point},
      {&b.flags, point},            {&b.zt, point},              {&b.r2, point},
      {&b.inten, point},            {&b.point_pixel, point},     {&b.pixel_key, pixel},
      {&b.pixel_point, pixel},      {&b.point_cell, point},      {&b.cell_zmin, cell},
      {&b.project_exact, ProjectStage::ExactListBytes(max_points)},
      {&b.cell_zmax, cell},         {&b.cell_count, cell},       {&b.cell_seed_mode, cell},
      {&b.cell_plane, 8 * cell},    {&b.coarse, point},
      {&b.coarse_scratch, CoarseSegmentStage::ScratchBytes(cells)},
      {&b.pixel_filled, pixel},     {&b.f_range, pixel},         {&b.f_inten, pixel},
      {&b.f_height, pixel},         {&b.f_slope, pixel},         {&b.f_edge_l, pixel},
      {&b.f_edge_r, pixel},         {&b.f_varz, pixel},          {&b.f_vari, pixel},
      {&b.feature_pack, FeatureMapsStage::PackBytes(pixels)},
      {&b.pixel_class, pixel},      {&b.pixel_fused, pixel},     {&b.pixel_grown, pixel},
      {&b.pixel_comp, pixel},       {&b.pixel_label, pixel},
      {&b.grow_reach, GrowStage::ReachBytes(pixels)},           {&b.grow_sizes, pixel},
      {&b.label_why, BackProjectStage::LabelWhyBytes(max_points)}};
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
    } names[] = {
        {&b.points, "points", &points_need},      {&b.ring, "ring", &points_need},
        {&b.flags, "flags", &points_need},        {&b.zt, "zt", &points_need},
        {&b.r2, "r2", &points_need},              {&b.inten, "inten", &points_need},
        {&b.point_pixel, "point_pixel", &points_need},
        {&b.project_exact, "project_exact", &points_need},
        {&b.point_cell, "point_cell", &points_need},
        {&b.coarse, "coarse", &points_need},      {&b.label_why, "label_why", &points_need},
        {&b.pixel_key, "pixel_key", &pixels_need}, {&b.pixel_point, "pixel_point", &pixels_need},
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
  for (const auto& s : sizes) LPIR_VK_RETURN_IF_ERROR(make(*s.buffer, s.bytes));
  LPIR_VK_RETURN_IF_ERROR(table(b.column_dir, tables.column_dir));
  LPIR_VK_RETURN_IF_ERROR(table(b.beam_bound, tables.beam_bound));
  LPIR_VK_RETURN_IF_ERROR(table(b.beam_origin, tables.beam_origin));
  LPIR_VK_RETURN_IF_ERROR(table(b.ring_bound2, tables.ring_bound2));
  LPIR_VK_RETURN_IF_ERROR(table(b.ring_inner, tables.ring_inner));
  {
    LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(device));
    const struct {
      const Buffer* buffer;
      const std::vector<float>* values;
    } uploads[] = {{&b.column_dir, &tables.column_dir},
                   {&b.beam_bound, &tables.beam_bound},
                   {&b.beam_origin, &tables.beam_origin},
                   {&b.ring_bound2, &tables.ring_bound2},
                   {&b.ring_inner, &tables.ring_inner}};
    for (const auto& u : uploads)
      if (!u.values->empty())
        LPIR_VK_RETURN_IF_ERROR(
            transfer.Upload(*u.buffer, u.values->data(), 4 * u.values->size()));
  }

  PrepareBuffers prepare{&b.params, &b.points, &b.ring, &b.flags, &b.zt, &b.r2, &b.inten};
  ProjectBuffers project{&b.params,      &b.points,     &b.ring,        &b.flags,
                         &b.r2,          &b.column_dir, &b.beam_bound,  &b.beam_origin,
                         &b.point_pixel, &b.pixel_key,  &b.pixel_point, &b.project_exact};
  GridReduceBuffers grid{&b.params,      &b.flags,      &b.r2,        &b.zt,       &b.point_pixel,
                         &b.ring_bound2, &b.point_cell, &b.cell_zmin, &b.cell_zmax, &b.cell_count};
  CoarseSegmentBuffers coarse{&b.params,     &b.points,         &b.zt,         &b.point_cell,
                              &b.cell_zmin,  &b.cell_zmax,      &b.cell_count, &b.ring_inner,
                              &b.cell_seed_mode, &b.cell_plane, &b.coarse,     &b.coarse_scratch};
  FeatureMapsBuffers features{&b.params,   &b.pixel_point, &b.r2,       &b.zt,     &b.inten,
                              &b.pixel_filled, &b.f_range, &b.f_inten,  &b.f_height,
                              &b.f_slope,  &b.f_edge_l,    &b.f_edge_r, &b.f_varz, &b.f_vari,
                              &b.feature_pack};
  ClassifyPixelsBuffers classify{&b.params,   &b.pixel_filled, &b.f_edge_l, &b.f_edge_r,
                                 &b.f_slope,  &b.f_varz,       &b.f_vari,   &b.pixel_class};
  FuseBuffers fuse{&b.params,       &b.pixel_class, &b.pixel_point, &b.coarse,
                   &b.pixel_filled, &b.f_range,     &b.f_height,    &b.pixel_fused};
  GrowBuffers grow{&b.params,      &b.pixel_fused, &b.f_inten,      &b.f_height,
                   &b.f_range,     &b.pixel_grown, &b.pixel_comp,   &b.pixel_label,
                   &b.grow_reach,  &b.grow_sizes};
  BackProjectBuffers back{&b.params, &b.flags,  &b.point_pixel, &b.pixel_point,
                          &b.pixel_label, &b.f_range, &b.f_height, &b.r2,
                          &b.zt,     &b.coarse, &b.label_why};
  LPIR_VK_ASSIGN_OR_RETURN(PrepareStage s1, PrepareStage::Create(device, prepare));
  LPIR_VK_ASSIGN_OR_RETURN(ProjectStage s2, ProjectStage::Create(device, project));
  LPIR_VK_ASSIGN_OR_RETURN(GridReduceStage s3, GridReduceStage::Create(device, grid));
  LPIR_VK_ASSIGN_OR_RETURN(CoarseSegmentStage s4, CoarseSegmentStage::Create(device, coarse));
  LPIR_VK_ASSIGN_OR_RETURN(FeatureMapsStage s5, FeatureMapsStage::Create(device, features));
  LPIR_VK_ASSIGN_OR_RETURN(ClassifyPixelsStage s6, ClassifyPixelsStage::Create(device, classify));
  LPIR_VK_ASSIGN_OR_RETURN(FuseStage s7, FuseStage::Create(device, fuse));
  LPIR_VK_ASSIGN_OR_RETURN(GrowStage s8, GrowStage::Create(device, grow));
  LPIR_VK_ASSIGN_OR_RETURN(BackProjectStage s9, BackProjectStage::Create(device, back));
  fp.stages_.reset(new Stages{std::move(s1), std::move(s2), std::move(s3), std::move(s4),
                              std::move(s5), std::move(s6), std::move(s7), std::move(s8),
                              std::move(s9)});

  const bool timed = device.timestamp_valid_bits() != 0;
  for (uint32_t i = 0; i < slots; ++i) {
    LPIR_VK_ASSIGN_OR_RETURN(CommandBuffer cmd, CommandBuffer::Create(device));
    LPIR_VK_ASSIGN_OR_RETURN(Fence fence, Fence::Create(device));
    LPIR_VK_ASSIGN_OR_RETURN(Buffer upload,
                             Buffer::Create(device, upload_bytes, MemoryKind::kHostVisible));
    LPIR_VK_ASSIGN_OR_RETURN(Buffer download,
                             Buffer::Create(device, download_bytes, MemoryKind::kHostVisible));
    fp.device_bytes_ += upload.size() + download.size();
    Slot slot{std::move(cmd), std::move(fence), std::move(upload), std::move(download), {}};
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
    const Status status = fp.Record(first, /*has_ring=*/true);
    first.n = 0;
    if (!status.ok())
      return PipelineError("max_points " + std::to_string(max_points) + ": " + status.message());
  }
  return fp;
}

Status FramePipeline::Submit(uint32_t index, const Cloud& cloud) {
  if (index >= slots_.size() || slots_[index].busy)
    return PipelineError("slot " + std::to_string(index) + " is not free");
  const uint64_t n = cloud.size();
  if (n > max_points_)
    return PipelineError("the cloud has " + std::to_string(n) +
                         " points, more than the pipeline's maximum of " +
                         std::to_string(max_points_));
  const bool has_ring = !cloud.ring.empty();
  if (has_ring && cloud.ring.size() != n)
    return PipelineError("the cloud has " + std::to_string(cloud.ring.size()) +
                         " ring entries for " + std::to_string(n) + " points");
  Slot& slot = slots_[index];
  auto* upload = static_cast<char*>(slot.upload.mapped());
  if (n) std::memcpy(upload, cloud.xyzi.data(), 16 * n);
  if (has_ring && n) std::memcpy(upload + 16 * VkDeviceSize(max_points_), cloud.ring.data(), 4 * n);
  slot.n = uint32_t(n);
  slot.has_ring = has_ring;
  LPIR_VK_RETURN_IF_ERROR(Record(slot, has_ring));
  last_counts_ = slot.cmd.counts();
  LPIR_VK_RETURN_IF_ERROR(slot.cmd.Submit(slot.fence));
  slot.busy = true;
  slot.serial = ++submitted_;
  return Status();
}

Status FramePipeline::Record(Slot& slot, bool has_ring) {
  Buffers& b = *buffers_;
  Stages& s = *stages_;
  CommandBuffer& cmd = slot.cmd;
  const uint32_t n = slot.n;
  const VkDeviceSize point = 4 * VkDeviceSize(max_points_);
  const TimestampQueries* q = slot.queries.empty() ? nullptr : &slot.queries[0];
  uint32_t stamp = 0;
  auto time = [&] {
    if (q) cmd.WriteTimestamp(*q, stamp++);
  };

  LPIR_VK_RETURN_IF_ERROR(cmd.Begin());
  if (q) cmd.ResetQueries(*q);
  time();
  // The frames before this one in the queue have finished with the shared buffers.
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
  // frame has touched yet; the head barrier ordered them after the previous frame.
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
  return cmd.End();
}

Status FramePipeline::Collect(uint32_t index, Frame& out, bool all_buffers, FrameTimes* times) {
  if (index >= slots_.size() || !slots_[index].busy)
    return PipelineError("slot " + std::to_string(index) + " holds no submitted frame");
  Slot& slot = slots_[index];
  if (all_buffers)
    for (const Slot& other : slots_)
      if (other.busy && other.serial > slot.serial)
        return PipelineError("all buffers of a frame are only readable before the next frame is "
                             "submitted (collect this slot without all_buffers)");
  LPIR_VK_RETURN_IF_ERROR(slot.fence.WaitAndReset());
  slot.busy = false;
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
    *times = FrameTimes{-1, {-1, -1, -1, -1, -1, -1, -1, -1, -1}, -1, -1};
    if (!slot.queries.empty()) {
      double ns[kQueries];
      LPIR_VK_RETURN_IF_ERROR(slot.queries[0].Read(ns));
      times->upload_ms = (ns[1] - ns[0]) / 1e6;
      for (int k = 0; k < 9; ++k) times->stage_ms[k] = (ns[k + 2] - ns[k + 1]) / 1e6;
      times->download_ms = (ns[11] - ns[10]) / 1e6;
      times->total_ms = (ns[11] - ns[0]) / 1e6;
    }
  }

  if (all_buffers) {
    const Buffers& b = *buffers_;
    LPIR_VK_ASSIGN_OR_RETURN(Transfer transfer, Transfer::Create(context_->device()));
    Status status;
    auto read = [&](const Buffer& src, auto& dst, size_t count) {
      dst.resize(count);
      if (status.ok() && count)
        status = transfer.Download(src, dst.data(), count * sizeof(dst[0]));
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
