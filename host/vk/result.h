// The result types of the Vulkan plumbing: every factory returns Result<T> (the object or an
// Error), every fallible action a Status. An Error is one message naming the failing call and its
// VkResult, ready for the user ("vkCreateBuffer: VK_ERROR_OUT_OF_DEVICE_MEMORY (-2) ...").
#pragma once
#include <vulkan/vulkan.h>

#include <cassert>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace lpir::vk {

struct Error {
  std::string message;
  VkResult result = VK_ERROR_UNKNOWN;  // VK_SUCCESS when no Vulkan call failed (a missing feature)
  // No Vulkan implementation or no physical device at all: tests skip instead of failing.
  bool no_device = false;
  // A GPU was asked for (Device::Create's gpu_only) and every usable device is a CPU driver.
  bool cpu_driver_only = false;
};

// "VK_ERROR_OUT_OF_DEVICE_MEMORY (-2)".
std::string VkResultName(VkResult result);

// The Error of a failed call: "<call>: <VkResultName> (<what>)", or without the parenthesis when
// `what` is empty.
Error CallError(const char* call, VkResult result, const std::string& what = "");

// An error that is no failed Vulkan call (bad sizes, a missing fixed point): "<who>: <message>".
inline Error UsageError(const std::string& who, const std::string& message) {
  Error e;
  e.result = VK_ERROR_UNKNOWN;
  e.message = who + ": " + message;
  return e;
}

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)) {}  // NOLINT: implicit, for `return Error{...}`

  bool ok() const { return !error_.has_value(); }
  const Error& error() const {
    assert(!ok());
    return *error_;
  }
  // "" when ok.
  std::string message() const { return ok() ? std::string() : error_->message; }

 private:
  std::optional<Error> error_;
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}      // NOLINT: implicit, for `return value`
  Result(Error error) : v_(std::move(error)) {}  // NOLINT: implicit, for `return Error{...}`

  bool ok() const { return std::holds_alternative<T>(v_); }
  const Error& error() const {
    assert(!ok());
    return std::get<Error>(v_);
  }
  Status status() const { return ok() ? Status() : Status(error()); }
  std::string message() const { return ok() ? std::string() : error().message; }

  T& value() & { return std::get<T>(v_); }
  const T& value() const& { return std::get<T>(v_); }
  T&& value() && { return std::get<T>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

 private:
  std::variant<T, Error> v_;
};

}  // namespace lpir::vk

// Returns the Error of a failed Vulkan call from the enclosing function (a Status or Result).
#define LPIR_VK_CHECK(call_expr, call_name, what)                                                \
  do {                                                                                           \
    const VkResult lpir_vk_r_ = (call_expr);                                                     \
    if (lpir_vk_r_ != VK_SUCCESS) return ::lpir::vk::CallError((call_name), lpir_vk_r_, (what)); \
  } while (0)

// Returns the Error of a failed Status from the enclosing function.
#define LPIR_VK_RETURN_IF_ERROR(status_expr)         \
  do {                                               \
    ::lpir::vk::Status lpir_vk_s_ = (status_expr);   \
    if (!lpir_vk_s_.ok()) return lpir_vk_s_.error(); \
  } while (0)

#define LPIR_VK_CONCAT_INNER_(a, b) a##b
#define LPIR_VK_CONCAT_(a, b) LPIR_VK_CONCAT_INNER_(a, b)
// `LPIR_VK_ASSIGN_OR_RETURN(auto buffer, Buffer::Create(...));` declares (or assigns) the value,
// or returns the Error from the enclosing function.
#define LPIR_VK_ASSIGN_OR_RETURN(lhs, result_expr)                 \
  auto LPIR_VK_CONCAT_(lpir_vk_result_, __LINE__) = (result_expr); \
  if (!LPIR_VK_CONCAT_(lpir_vk_result_, __LINE__).ok())            \
    return LPIR_VK_CONCAT_(lpir_vk_result_, __LINE__).error();     \
  lhs = std::move(LPIR_VK_CONCAT_(lpir_vk_result_, __LINE__)).value()
