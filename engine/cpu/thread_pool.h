#pragma once
// A fixed pool of worker threads for the CPU reference backend. parallel_for splits [0, n) into
// contiguous chunks (chunk k before chunk k+1), which the stable sort relies on.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace masav::cpu {

class ThreadPool {
 public:
  explicit ThreadPool(unsigned threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned size() const { return unsigned(workers_.size()) + 1; }  // the caller works too

  // Calls fn(chunk, begin, end) for `chunks` contiguous pieces of [0, n); blocks until done.
  void run_chunks(size_t n, size_t chunks,
                  const std::function<void(size_t chunk, size_t begin, size_t end)>& fn);
  // Splits [0, n) into pieces of at least `grain` items, about 4 per thread.
  void parallel_for(size_t n, size_t grain, const std::function<void(size_t, size_t)>& fn);

 private:
  void worker_loop();
  void run_pending(std::unique_lock<std::mutex>& lock);

  // Spins up to kSpinIterations on `ready` before the caller sleeps on the condition variable:
  // a kernel's chunks often follow the last within microseconds (a DFSPH step runs some forty),
  // and waking a sleeping thread costs tens of microseconds on a virtual machine.
  template <class Ready>
  static void spin_until(Ready&& ready);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(size_t, size_t, size_t)>* job_ = nullptr;
  size_t job_n_ = 0, job_chunks_ = 0, next_chunk_ = 0;
  // Written under mutex_; read without it while spinning.
  std::atomic<size_t> finished_chunks_ = 0;
  std::atomic<bool> stop_ = false;
  std::atomic<unsigned> generation_ = 0;
  std::exception_ptr error_;
};

// Threads the CPU backend uses unless told (CpuTuning::threads): the hardware's.
unsigned default_cpu_threads();

}  // namespace masav::cpu
