#include "engine/cpu/thread_pool.h"

#include <algorithm>
#include <string>
#include <utility>

#include "engine/core/error.h"

namespace masav::cpu {

namespace {
// About 0.1 ms of polling (a pause takes tens to a hundred and more cycles, by processor): longer
// than a wake-up, short enough that an idle pool, or one sharing its cores, soon sleeps.
constexpr int kSpinIterations = 4000;

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}
}  // namespace

template <class Ready>
void ThreadPool::spin_until(Ready&& ready) {
  for (int i = 0; i < kSpinIterations && !ready(); ++i) cpu_relax();
}

ThreadPool::ThreadPool(unsigned threads) {
  for (unsigned i = 1; i < std::max(1u, threads); ++i)
    workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::run_pending(std::unique_lock<std::mutex>& lock) {
  while (job_ && next_chunk_ < job_chunks_) {
    const size_t chunk = next_chunk_++;
    const auto* job = job_;
    const size_t n = job_n_, chunks = job_chunks_;
    lock.unlock();
    try {
      (*job)(chunk, n * chunk / chunks, n * (chunk + 1) / chunks);
    } catch (...) {
      std::lock_guard g(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    lock.lock();
    if (++finished_chunks_ == job_chunks_) done_.notify_all();
  }
}

void ThreadPool::worker_loop() {
  std::unique_lock lock(mutex_);
  unsigned seen = generation_;
  auto ready = [&] { return stop_ || generation_ != seen; };
  for (;;) {
    if (!ready()) {
      lock.unlock();
      spin_until(ready);
      lock.lock();
    }
    wake_.wait(lock, ready);
    if (stop_) return;
    seen = generation_;
    run_pending(lock);
  }
}

void ThreadPool::run_chunks(size_t n, size_t chunks,
                            const std::function<void(size_t, size_t, size_t)>& fn) {
  if (chunks == 0) return;
  if (chunks == 1 || workers_.empty()) {
    for (size_t c = 0; c < chunks; ++c) fn(c, n * c / chunks, n * (c + 1) / chunks);
    return;
  }
  std::unique_lock lock(mutex_);
  job_ = &fn;
  job_n_ = n;
  job_chunks_ = chunks;
  next_chunk_ = 0;
  finished_chunks_ = 0;
  error_ = nullptr;
  ++generation_;
  wake_.notify_all();
  run_pending(lock);
  auto done = [&] { return finished_chunks_ == chunks; };
  if (!done()) {
    lock.unlock();
    spin_until(done);
    lock.lock();
  }
  done_.wait(lock, done);
  job_ = nullptr;
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void ThreadPool::parallel_for(size_t n, size_t grain,
                              const std::function<void(size_t, size_t)>& fn) {
  if (n == 0) return;
  const size_t max_chunks = std::max<size_t>(1, n / std::max<size_t>(1, grain));
  const size_t chunks = std::min<size_t>(max_chunks, size_t(size()) * 4);
  run_chunks(n, chunks, [&](size_t, size_t b, size_t e) { fn(b, e); });
}

unsigned default_cpu_threads() {
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace masav::cpu
