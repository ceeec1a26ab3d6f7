#include "render/layer_bridge.h"

#include <cstring>
#include <vector>

namespace masav::render {

bool LayerBridge::fresh(const std::string& slot, const BufferImpl& src, uint64_t version) const {
  const auto it = slots_.find(slot);
  return it != slots_.end() && it->second.source == &src && it->second.version == version &&
         version != 0 && it->second.copy;
}

std::shared_ptr<vk::Allocation> LayerBridge::store(const std::string& slot, const BufferImpl& src,
                                                   uint64_t version, const void* data,
                                                   size_t bytes) {
  Slot& s = slots_[slot];
  if (!s.copy || s.copy->bytes < bytes)
    s.copy = vk::allocate(dev_.ctx(), bytes, vk::MemoryUse::upload, "render copy of " + slot);
  if (bytes) std::memcpy(s.copy->mapped, data, bytes);
  s.source = &src;
  s.version = version;
  bytes_copied_ += bytes;
  return s.copy;
}

std::shared_ptr<vk::Allocation> LayerBridge::positions(const std::string& slot,
                                                       const Buffer<Real4>& b, uint32_t count,
                                                       uint64_t version) {
  if (dev_.shared()) return dev_.shared()->vulkan_buffer(b.impl());
  if (fresh(slot, b.impl(), version)) return slots_[slot].copy;
  std::vector<Vec4f> host = dev_.compute().download_f32(b);
  host.resize(count);
  return store(slot, b.impl(), version, host.data(), host.size() * sizeof(Vec4f));
}

std::shared_ptr<vk::Allocation> LayerBridge::words(const std::string& slot, const BufferImpl& b,
                                                   uint64_t version) {
  if (dev_.shared()) return dev_.shared()->vulkan_buffer(b);
  if (fresh(slot, b, version)) return slots_[slot].copy;
  Backend& c = dev_.compute();
  if (b.kind() == ElemKind::real || b.kind() == ElemKind::real4) {
    const size_t scalars = b.count() * (b.kind() == ElemKind::real4 ? 4 : 1);
    std::vector<float> f(scalars);
    if (c.real_bytes() == 8) {
      std::vector<double> d(scalars);
      c.download_bytes(b, d.data(), scalars * 8, 0);
      for (size_t i = 0; i < scalars; ++i) f[i] = float(d[i]);
    } else {
      c.download_bytes(b, f.data(), scalars * 4, 0);
    }
    return store(slot, b, version, f.data(), f.size() * 4);
  }
  std::vector<uint32_t> w(b.count());
  c.download_bytes(b, w.data(), w.size() * 4, 0);
  return store(slot, b, version, w.data(), w.size() * 4);
}

}  // namespace masav::render
