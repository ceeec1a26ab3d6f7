#pragma once
// A scene as a graph of stages with versioned inputs (SPEC §4, "skip what a scene doesn't
// need"). Inputs are what the outside world changes: parameters ("particles.count"), the time,
// the viewpoint. A stage names the inputs and the other stages it reads; it runs only when one
// of them changed since its last run, and it is created -- buffers allocated, kernels first
// dispatched (so pipelines compiled) -- only when a target of update() reaches it.
//
// The atom scene's needs map onto this directly: light at unit power is a stage reading the
// cloud, the table and the source position; "light" reads it and the source power, so a power
// change reruns only the rescale; viewer attenuation and the raymarch read the view, so a view
// change reruns only them; the scattering table stage reads its parameters and fills itself
// from the disk cache when it can.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace masav {
class Backend;
}

namespace masav::scene {

class Stage {
 public:
  virtual ~Stage() = default;
  virtual void run() = 0;
  // Whether the last run() restored the output from the disk cache (stage_cache.h) instead of
  // computing it.
  virtual bool loaded_from_cache() const { return false; }
};

// A stage made from a lambda, for stages whose state lives in the scene.
class LambdaStage final : public Stage {
 public:
  explicit LambdaStage(std::function<void()> fn) : fn_(std::move(fn)) {}
  void run() override { fn_(); }

 private:
  std::function<void()> fn_;
};

struct StageCounters {
  std::string name;
  bool created = false;
  uint64_t runs = 0;        // times it ran
  uint64_t skips = 0;       // updates that reached it while it was up to date
  uint64_t cache_hits = 0;  // runs that loaded the output from the disk cache
  double last_ms = 0;       // device time of its last run
  double total_ms = 0;
};

// What one update() did.
struct UpdateReport {
  std::vector<std::string> ran, skipped, created, cached;
};

class StageGraph {
 public:
  // An input the outside world changes; `touch` marks it changed.
  void add_input(std::string name);
  bool has_input(std::string_view name) const;
  void touch(std::string_view input);
  // Touches the input if the graph has one of that name (parameters no stage reads are fine).
  bool touch_if_present(std::string_view input);

  // `create` builds the stage (allocating what it needs) the first time a target reaches it.
  void add_stage(std::string name, std::vector<std::string> inputs,
                 std::function<std::unique_ptr<Stage>()> create);

  // Brings `targets` up to date: creates the stages they reach that do not exist yet and runs,
  // in dependency order, each reached stage that never ran or whose inputs changed since its
  // last run. With a backend, each run is bracketed by device timestamps (per-stage times).
  UpdateReport update(std::span<const std::string> targets, Backend* timing = nullptr);
  // Whether update() would run `stage` (or a stage it reads) for a change of any input other
  // than `ignored_input`: the demo tells a moving view from a refinement it asked for itself.
  bool pending(std::string_view stage, std::string_view ignored_input = {}) const;

  // The stage's version: changes whenever it runs (0 = never ran). Consumers outside the graph
  // (the renderer's copy of a CPU buffer) use it to tell whether an output changed.
  uint64_t version(std::string_view name) const;
  bool created(std::string_view name) const;
  std::vector<StageCounters> counters() const;  // in declaration order
  const StageCounters& counters(std::string_view stage) const;
  void reset_counters();  // keeps the stages, zeroes runs/skips (tests measure from here)

 private:
  struct Node {
    std::string name;
    bool is_input = false;
    std::vector<std::string> inputs;
    std::function<std::unique_ptr<Stage>()> create;
    std::unique_ptr<Stage> stage;
    uint64_t version = 0;
    std::map<std::string, uint64_t, std::less<>> seen;  // input versions at the last run
    StageCounters counters;
  };
  Node& node(std::string_view name);
  const Node& node(std::string_view name) const;
  void visit(const std::string& name, std::vector<Node*>& order, std::map<std::string, int>& mark);

  std::vector<std::unique_ptr<Node>> nodes_;
  std::map<std::string, Node*, std::less<>> by_name_;
  uint64_t clock_ = 0;
};

// Prints the counters as a table: stage, created, runs, skipped, last and mean device time.
std::string format_stage_stats(const std::vector<StageCounters>& counters);

}  // namespace masav::scene
