// The Vulkan plumbing of host/vk/: device choice and its error messages, the validation message
// count, buffers through the staging path (chunked, at offsets), fill and copy commands,
// timestamps.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "host/vk/buffer.h"
#include "host/vk/command_buffer.h"
#include "host/vk/context.h"
#include "host/vk/fence.h"
#include "host/vk/timestamp_queries.h"
#include "host/vk/transfer.h"
#include "tests/vk_test_util.h"

namespace lpir {
namespace {

class VkContext : public test::VkTest {};

TEST_F(VkContext, DescribesEveryDevice) {
  vk::Result<std::vector<std::string>> lines = vk::Device::Describe(context().instance());
  ASSERT_TRUE(lines.ok()) << lines.message();
  ASSERT_FALSE(lines->empty());
  bool listed = false;
  for (const std::string& line : lines.value()) {
    std::printf("[vulkan] %s\n", line.c_str());
    listed |=
        line.find(device().name()) != std::string::npos && line.find("usable") != std::string::npos;
  }
  EXPECT_TRUE(listed) << "the chosen device is not listed as usable";
}

TEST_F(VkContext, PicksTheDeviceByNameOrIndexAndSaysWhyNot) {
  const std::string name = device().name();
  vk::Result<vk::Device> by_name = vk::Device::Create(context().instance(), name.substr(0, 4));
  ASSERT_TRUE(by_name.ok()) << by_name.message();
  EXPECT_EQ(by_name->name().substr(0, 4), name.substr(0, 4));

  vk::Result<vk::Device> unknown = vk::Device::Create(context().instance(), "no-such-gpu-x");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.message().find("no Vulkan device name contains \"no-such-gpu-x\""),
            std::string::npos)
      << unknown.message();
  EXPECT_NE(unknown.message().find(name), std::string::npos) << unknown.message();

  vk::Result<vk::Device> too_far = vk::Device::Create(context().instance(), "999");
  ASSERT_FALSE(too_far.ok());
  EXPECT_NE(too_far.message().find("no Vulkan device #999"), std::string::npos)
      << too_far.message();
}

TEST_F(VkContext, StagingTransfersAreChunkedAndOffset) {
  vk::Result<vk::Buffer> buffer = vk::Buffer::Create(device(), 40000, vk::MemoryKind::kDeviceLocal);
  ASSERT_TRUE(buffer.ok()) << buffer.message();
  EXPECT_EQ(buffer->mapped(), nullptr);
  vk::Result<vk::Transfer> transfer = vk::Transfer::Create(device(), 4096);  // 10 chunks
  ASSERT_TRUE(transfer.ok()) << transfer.message();
  std::vector<uint32_t> data(10000);
  std::iota(data.begin(), data.end(), 7u);
  ASSERT_TRUE(transfer->Upload(buffer.value(), data.data(), 40000).ok());
  const uint32_t patch[3] = {0xDEADBEEFu, 0xFFFFFFFFu, 0u};
  ASSERT_TRUE(transfer->Upload(buffer.value(), patch, sizeof(patch), 4 * 5000).ok());
  std::vector<uint32_t> back(10000, 1u);
  ASSERT_TRUE(transfer->Download(buffer.value(), back.data(), 40000).ok());
  data[5000] = patch[0], data[5001] = patch[1], data[5002] = patch[2];
  EXPECT_EQ(back, data);
  std::vector<uint32_t> tail(3);
  ASSERT_TRUE(transfer->Download(buffer.value(), tail.data(), 12, 4 * 9997).ok());
  EXPECT_EQ(tail, std::vector<uint32_t>(data.end() - 3, data.end()));

  const vk::Status beyond = transfer->Upload(buffer.value(), data.data(), 8, 39996);
  ASSERT_FALSE(beyond.ok());
  EXPECT_NE(beyond.message().find("upload of 8 bytes at offset 39996"), std::string::npos)
      << beyond.message();
}

TEST_F(VkContext, FillCopyAndTimestamps) {
  vk::Result<vk::Buffer> a = vk::Buffer::Create(device(), 4096, vk::MemoryKind::kDeviceLocal);
  vk::Result<vk::Buffer> b = vk::Buffer::Create(device(), 4096, vk::MemoryKind::kHostVisible);
  vk::Result<vk::CommandBuffer> cmd = vk::CommandBuffer::Create(device());
  vk::Result<vk::Fence> fence = vk::Fence::Create(device());
  ASSERT_TRUE(a.ok() && b.ok() && cmd.ok() && fence.ok());
  const bool timed = device().timestamp_valid_bits() != 0;
  vk::Result<vk::TimestampQueries> queries = vk::TimestampQueries::Create(device(), 2);
  ASSERT_EQ(queries.ok(), timed) << queries.message();

  for (uint32_t round = 0; round < 2; ++round) {  // a re-recorded command buffer, a reset fence
    ASSERT_TRUE(cmd->Begin().ok());
    if (timed) {
      cmd->ResetQueries(queries.value());
      cmd->WriteTimestamp(queries.value(), 0);
    }
    cmd->FillBuffer(a.value(), 0x01020304u + round);
    cmd->Barrier(VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    cmd->CopyBuffer(a.value(), b.value(), 4096);
    cmd->TransferToHost();
    if (timed) cmd->WriteTimestamp(queries.value(), 1);
    ASSERT_TRUE(cmd->End().ok());
    const vk::Status ran = cmd->SubmitAndWait(fence.value());
    ASSERT_TRUE(ran.ok()) << ran.message();
    const uint32_t* words = static_cast<const uint32_t*>(b->mapped());
    for (int i = 0; i < 1024; ++i) ASSERT_EQ(words[i], 0x01020304u + round) << i;
    if (timed) {
      double ns[2];
      ASSERT_TRUE(queries->Read(ns).ok());
      EXPECT_GE(ns[1], ns[0]);
    }
  }
}

// The count behind every "zero validation messages" assertion: a deliberate misuse must be seen.
// Its own instance, so the shared context's counts stay clean.
TEST(VkValidation, MessagesAreCounted) {
  vk::ContextOptions options = vk::ContextOptions::FromEnvironment();
  options.validation = true;
  vk::Result<vk::Context> context = vk::Context::Create(options);
  if (!context.ok() && context.error().no_device)
    GTEST_SKIP() << "no Vulkan device on this machine (" << context.message() << ")";
  ASSERT_TRUE(context.ok()) << context.message();
  ASSERT_EQ(context->validation_messages(), 0u);
  // VUID-VkBufferCreateInfo-sharingMode-00914: concurrent sharing without queue families (drivers
  // ignore the sharing mode of a buffer only one queue uses, so the call itself is harmless).
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = 256;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  info.sharingMode = VK_SHARING_MODE_CONCURRENT;
  info.queueFamilyIndexCount = 0;
  const VkDevice device = context->device().handle();
  VkBuffer buffer = VK_NULL_HANDLE;
  std::printf("[vulkan] a deliberate misuse follows; its message is expected:\n");
  std::fflush(stdout);
  if (vkCreateBuffer(device, &info, nullptr, &buffer) == VK_SUCCESS)
    vkDestroyBuffer(device, buffer, nullptr);
  EXPECT_GE(context->validation_messages(), 1u);
}

}  // namespace
}  // namespace lpir
