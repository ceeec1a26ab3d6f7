// CUDA backend, captures: the work recorded between begin_capture() and end_capture() (a block
// of SPH steps) becomes one CUDA graph, launched with one call, so that the device runs its
// kernels back to back instead of waiting for the host to launch each. A block's graph has the
// shape of the ones before it, with other parameters (dt, the buffers a swap exchanged):
// cudaGraphExecUpdate carries them into a kept executable graph, far cheaper than
// instantiating a new one; a graph of another shape (a shorter last block) replaces it. Two
// executable graphs take turns: a simulation keeps two blocks in flight, so the one updated
// is the one launched two blocks ago, whose stats the host has taken (it has finished).
#include <fmt/format.h>

#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"

namespace masav::cuda {
namespace {

// What a fault inside a graph can name: the graph, not the kernel (no launch returns between
// its kernels).
constexpr const char* kGraphLaunch =
    "a block of steps launched as one CUDA graph (--tune cuda.graphs=off, or "
    "cuda.sync_each_launch=on, to name the kernel)";

struct GraphGuard {
  cudaGraph_t g = nullptr;
  ~GraphGuard() {
    if (g) cudaGraphDestroy(g);
  }
};

}  // namespace

void CudaBackend::begin_capture() {
  if (!graphs_ || capturing_) return;
  // Thread-local: only this thread's calls that could break the capture are refused (with an
  // error), and leave_capture() ends it before each of them.
  check_stream(cudaStreamBeginCapture(stream_, cudaStreamCaptureModeThreadLocal), "capture",
               "cudaStreamBeginCapture");
  capturing_ = true;
}

void CudaBackend::end_capture() {
  leave_capture();
}

void CudaBackend::leave_capture() {
  if (!capturing_) return;
  capturing_ = false;
  GraphGuard graph;
  check_stream(cudaStreamEndCapture(stream_, &graph.g), "capture", "cudaStreamEndCapture");
  size_t nodes = 0;
  check(cudaGraphGetNodes(graph.g, nullptr, &nodes), "capture", "cudaGraphGetNodes");
  if (nodes == 0) return;
  cudaGraphExec_t& exec = graph_execs_[next_graph_exec_];
  next_graph_exec_ = (next_graph_exec_ + 1) % graph_execs_.size();
  if (exec) {
    cudaGraphExecUpdateResultInfo info{};
    if (cudaGraphExecUpdate(exec, graph.g, &info) != cudaSuccess) {
      (void)cudaGetLastError();  // another shape: not an error, a new graph
      cudaGraphExecDestroy(exec);
      exec = nullptr;
    }
  }
  if (!exec) {
    check(cudaGraphInstantiate(&exec, graph.g, 0), "capture", "cudaGraphInstantiate");
    ++counters_.graph_builds;
  }
  check_stream(cudaGraphLaunch(exec, stream_), "capture", "cudaGraphLaunch");
  ++counters_.graphs;
  last_kernel_ = kGraphLaunch;
  last_step_ = nullptr;
}

void CudaBackend::abort_capture() noexcept {
  if (!capturing_) return;
  capturing_ = false;
  cudaGraph_t g = nullptr;
  // The capture may have been invalidated by the error that brought us here: its status is
  // dropped with it.
  (void)cudaStreamEndCapture(stream_, &g);
  if (g) cudaGraphDestroy(g);
  (void)cudaGetLastError();
}

}  // namespace masav::cuda
