#include "render/png_queue.h"

#include "render/png.h"

namespace masav::render {

PngQueue::PngQueue(size_t depth) : depth_(std::max<size_t>(depth, 1)) {
  worker_ = std::thread([this] { work(); });
}

PngQueue::~PngQueue() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return jobs_.empty() && !busy_; });
    stop_ = true;
  }
  changed_.notify_all();
  worker_.join();
}

void PngQueue::rethrow() {
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

void PngQueue::push(std::string path, uint32_t width, uint32_t height, std::vector<uint8_t> rgba) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return jobs_.size() < depth_ || error_; });
  rethrow();
  jobs_.push_back({std::move(path), width, height, std::move(rgba)});
  changed_.notify_all();
}

void PngQueue::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return (jobs_.empty() && !busy_) || error_; });
  rethrow();
}

void PngQueue::work() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return !jobs_.empty() || stop_; });
      if (jobs_.empty()) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
      busy_ = true;
    }
    std::exception_ptr failure;
    try {
      write_png(job.path, job.width, job.height, job.rgba);
    } catch (...) {
      failure = std::current_exception();
    }
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
      if (failure && !error_) error_ = failure;
    }
    changed_.notify_all();
  }
}

}  // namespace masav::render
