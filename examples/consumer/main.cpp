// The smallest program against the installed package: the library's version and its backends.
#include <masav/masav.h>

#include <cstdio>

int main() {
  std::printf("masav %s (headers %s)\n", masav::version(), MASAV_VERSION);
  for (const masav::BackendStatus& b : masav::backend_report())
    std::printf("%-7s built=%d available=%d %s\n", b.name.c_str(), b.built, b.available,
                b.reason.c_str());
  return 0;
}
