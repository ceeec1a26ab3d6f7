// Registry entry points for CUDA: device discovery that never throws on a machine without a
// driver or a GPU (the backend is then listed as unavailable with the CUDA runtime's reason).
#include "cuda_ref/cuda_factory.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "cuda_ref/cuda_backend.h"
#include "engine/core/error.h"

namespace masav::cuda {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

}  // namespace

BackendStatus backend_status() {
  BackendStatus s;
  s.name = "cuda";
  s.built = true;
  int count = 0;
  const cudaError_t st = cudaGetDeviceCount(&count);
  if (st != cudaSuccess || count == 0) {
    (void)cudaGetLastError();
    s.reason = fmt::format("no CUDA device ({}); CUDA needs an NVIDIA GPU and its driver",
                           st == cudaSuccess ? "none found" : cudaGetErrorString(st));
    return s;
  }
  for (int i = 0; i < count; ++i) {
    cudaDeviceProp p{};
    if (cudaGetDeviceProperties(&p, i) != cudaSuccess) continue;
    DeviceStatus d;
    d.index = unsigned(i);
    d.name = p.name;
    d.type = p.integrated ? "integrated" : "discrete";
    d.detail = fmt::format("sm_{}{}, {} MiB", p.major, p.minor, p.totalGlobalMem >> 20);
    d.usable = true;
    s.devices.push_back(d);
  }
  s.available = !s.devices.empty();
  if (!s.available) s.reason = "CUDA devices could not be queried";
  return s;
}

std::unique_ptr<Backend> create_backend(std::string_view device, const Tuning& tuning) {
  const BackendStatus s = backend_status();
  if (!s.available) throw Error("cuda", "", s.reason, "use --backend vulkan or --backend cpu");
  int chosen = 0;
  if (!device.empty()) {
    const std::string sel(device);
    char* end = nullptr;
    const long idx = std::strtol(sel.c_str(), &end, 10);
    chosen = -1;
    if (end && *end == '\0') {
      if (idx >= 0 && size_t(idx) < s.devices.size()) chosen = int(idx);
    } else {
      for (const auto& d : s.devices)
        if (chosen < 0 && lower(d.name).find(lower(sel)) != std::string::npos) chosen = int(d.index);
    }
    if (chosen < 0)
      throw_invalid("cuda", "device", sel,
                    fmt::format("an index in [0, {}] or part of a device name",
                                s.devices.size() - 1));
  }
  return std::make_unique<CudaBackend>(chosen, tuning);
}

}  // namespace masav::cuda
