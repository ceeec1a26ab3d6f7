#pragma once
// PNG frames encoded on a worker thread while the next frame is computed and drawn (encoding a
// 960x540 frame with stb takes longer than drawing it on lavapipe). At most `depth` frames wait;
// an encoding or write error surfaces on the next push() or on finish().
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace masav::render {

class PngQueue {
 public:
  explicit PngQueue(size_t depth = 2);
  ~PngQueue();  // waits for the frames already queued (every file is complete)
  PngQueue(const PngQueue&) = delete;
  PngQueue& operator=(const PngQueue&) = delete;

  void push(std::string path, uint32_t width, uint32_t height, std::vector<uint8_t> rgba);
  // Waits until every queued frame is written; rethrows the first error.
  void finish();

 private:
  struct Job {
    std::string path;
    uint32_t width, height;
    std::vector<uint8_t> rgba;
  };
  void work();
  void rethrow();

  size_t depth_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  bool busy_ = false, stop_ = false;
  std::exception_ptr error_;
  std::thread worker_;
};

}  // namespace masav::render
