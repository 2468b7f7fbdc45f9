// Shared by the Vulkan tests: one context per test process, validation on, on the device that
// VK_ICD_FILENAMES (lavapipe under ctest) and LPIR_VK_DEVICE give; a fixture that skips when the
// machine has no Vulkan device and fails a test that produced any validation message; and a
// global check, after the context is destroyed, that its destruction (leak reports) was silent.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <string>

#include "host/vk/context.h"

namespace lpir::test {

class VkEnvironment : public ::testing::Environment {
 public:
  // The context, made on first use; nullptr (error() says why) when it could not be made.
  vk::Context* context() {
    if (!tried_) {
      tried_ = true;
      vk::ContextOptions options = vk::ContextOptions::FromEnvironment();
      options.validation = true;
      vk::Result<vk::Context> made = vk::Context::Create(options);
      if (made.ok()) {
        context_ = std::make_unique<vk::Context>(std::move(made).value());
        std::printf("[vulkan] device: %s\n", context_->device().name().c_str());
      } else {
        error_ = made.error();
      }
    }
    return context_.get();
  }
  const vk::Error& error() const { return error_; }

  void TearDown() override {
    if (!context_) return;
    EXPECT_EQ(context_->validation_messages(), 0u)
        << "Vulkan validation messages were printed (see above)";
    const uint64_t before = vk::Instance::TotalMessages();
    context_.reset();
    EXPECT_EQ(vk::Instance::TotalMessages(), before)
        << "destroying the Vulkan context printed validation messages (leaks? see above)";
  }

 private:
  bool tried_ = false;
  std::unique_ptr<vk::Context> context_;
  vk::Error error_;
};

inline VkEnvironment* const kVkEnvironment =
    static_cast<VkEnvironment*>(::testing::AddGlobalTestEnvironment(new VkEnvironment));

// Fixture of every Vulkan test: `context()` is valid in the test body.
class VkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = kVkEnvironment->context();
    if (!context_) {
      const vk::Error& e = kVkEnvironment->error();
      if (e.no_device)
        GTEST_SKIP() << "no Vulkan device on this machine (" << e.message
                     << "); install mesa-vulkan-drivers for lavapipe";
      FAIL() << "Vulkan set-up failed: " << e.message;
    }
    messages_before_ = vk::Instance::TotalMessages();
  }
  void TearDown() override {
    if (context_) {
      EXPECT_EQ(vk::Instance::TotalMessages(), messages_before_)
          << "Vulkan validation messages were printed (see above)";
    }
  }

  const vk::Context& context() const { return *context_; }
  const vk::Device& device() const { return context_->device(); }

 private:
  vk::Context* context_ = nullptr;
  uint64_t messages_before_ = 0;
};

}  // namespace lpir::test
