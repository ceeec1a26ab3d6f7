// Sorts the same random keys on every backend this machine has and compares each result with
// the CPU reference's, bit for bit. Usage: sort_backends [COUNT]
#include <masav/masav.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

int main(int argc, char** argv) try {
  const uint32_t n = argc > 1 ? uint32_t(std::strtoul(argv[1], nullptr, 10)) : 100000;
  std::mt19937 rng(42);
  std::vector<uint32_t> keys(n);
  for (uint32_t& k : keys) k = rng();

  // The CPU reference first, then every other backend against it.
  std::vector<std::string> names = {"cpu"};
  for (const std::string& name : masav::usable_backends())
    if (name != "cpu") names.push_back(name);
  std::vector<uint32_t> reference;
  int mismatches = 0;
  for (const std::string& name : names) {
    auto backend = masav::open_backend(name);
    auto buffer = masav::to_device<uint32_t>(*backend, std::span<const uint32_t>(keys));
    masav::RadixSortParams p;
    p.n = n;
    backend->radix_sort(p, buffer, nullptr);
    const std::vector<uint32_t> sorted = masav::to_host(*backend, buffer);
    if (name == "cpu") reference = sorted;
    std::printf("%-7s %-40s first %u last %u\n", name.c_str(), backend->caps().device_name.c_str(),
                sorted.front(), sorted.back());
    if (sorted != reference) {
      std::printf("%s disagrees with the CPU reference\n", name.c_str());
      ++mismatches;
    }
  }
  return mismatches == 0 ? 0 : 1;
} catch (const masav::Error& e) {
  std::fprintf(stderr, "sort_backends: %s\n", e.what());
  return 2;
}
