#pragma once
// What `masav info` and the registry know about a backend before creating it.
#include <string>
#include <vector>

namespace masav {

struct DeviceStatus {
  unsigned index = 0;
  std::string name;
  std::string type;    // discrete, integrated, cpu, ...
  std::string detail;  // API version, memory, compute capability
  bool usable = false;
  std::string reason;  // why not usable
};

struct BackendStatus {
  std::string name;
  bool built = false;
  bool available = false;
  std::string reason;  // why not built or not available
  std::vector<DeviceStatus> devices;
};

}  // namespace masav
