#pragma once
// Typed buffer handles. A Buffer<T> owns one allocation of the backend that created it; the
// element type is part of the handle's type, so a kernel taking Buffer<uint32_t> cannot be given
// positions by mistake. Storage is backend-specific (BufferImpl is subclassed per backend).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "engine/core/types.h"

namespace masav {

enum class ElemKind : uint8_t { u32, i32, f32, real, real4 };

const char* elem_kind_name(ElemKind kind);
// Bytes per element: `real_bytes` is 4 on the GPU backends and 8 on the CPU reference.
size_t elem_bytes(ElemKind kind, size_t real_bytes);

// The element kind of a buffer's element type.
template <class T>
consteval ElemKind elem_kind_of() {
  if constexpr (std::is_same_v<T, uint32_t>) return ElemKind::u32;
  else if constexpr (std::is_same_v<T, int32_t>) return ElemKind::i32;
  else if constexpr (std::is_same_v<T, float>) return ElemKind::f32;
  else if constexpr (std::is_same_v<T, Real>) return ElemKind::real;
  else if constexpr (std::is_same_v<T, Real4>) return ElemKind::real4;
  else static_assert(sizeof(T) == 0, "no buffer holds this element type");
}

class DeviceApi;

// Backend-owned storage. Each backend subclasses it; kernels downcast after checking `owner`.
class BufferImpl {
 public:
  BufferImpl(const DeviceApi* owner, ElemKind kind, size_t count, size_t bytes, std::string label)
      : owner_(owner), kind_(kind), count_(count), bytes_(bytes), label_(std::move(label)) {}
  virtual ~BufferImpl() = default;
  BufferImpl(const BufferImpl&) = delete;
  BufferImpl& operator=(const BufferImpl&) = delete;

  const DeviceApi* owner() const { return owner_; }
  ElemKind kind() const { return kind_; }
  size_t count() const { return count_; }
  size_t bytes() const { return bytes_; }
  const std::string& label() const { return label_; }

 private:
  const DeviceApi* owner_;
  ElemKind kind_;
  size_t count_;
  size_t bytes_;
  std::string label_;
};

template <class T>
class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(std::unique_ptr<BufferImpl> impl) : impl_(std::move(impl)) {}

  size_t size() const { return impl_ ? impl_->count() : 0; }
  bool valid() const { return impl_ != nullptr; }
  explicit operator bool() const { return valid(); }
  BufferImpl& impl() { return *impl_; }
  const BufferImpl& impl() const { return *impl_; }

 private:
  std::unique_ptr<BufferImpl> impl_;
};

// The storage behind a kernel's buffer argument of any kind: a buffer, an optional one (null when
// absent or never created), or untyped storage.
template <class T>
const BufferImpl* impl_of(const Buffer<T>& b) {
  return b.valid() ? &b.impl() : nullptr;
}
template <class T>
const BufferImpl* impl_of(const Buffer<T>* b) {
  return b && b->valid() ? &b->impl() : nullptr;
}
inline const BufferImpl* impl_of(const BufferImpl& b) {
  return &b;
}

}  // namespace masav
