#include "engine/scene/stage_graph.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/kernels/backend.h"

namespace masav::scene {

void StageGraph::add_input(std::string name) {
  if (by_name_.count(name))
    throw Error("", "stage graph", fmt::format("'{}' is declared twice", name), "internal error");
  auto n = std::make_unique<Node>();
  n->name = name;
  n->is_input = true;
  n->version = ++clock_;
  n->counters.name = name;
  by_name_[name] = n.get();
  nodes_.push_back(std::move(n));
}

bool StageGraph::has_input(std::string_view name) const {
  auto it = by_name_.find(name);
  return it != by_name_.end() && it->second->is_input;
}

void StageGraph::touch(std::string_view input) {
  Node& n = node(input);
  if (!n.is_input)
    throw Error("", "stage graph", fmt::format("'{}' is a stage, not an input", input),
                "internal error: only inputs are touched");
  n.version = ++clock_;
}

bool StageGraph::touch_if_present(std::string_view input) {
  if (!has_input(input)) return false;
  touch(input);
  return true;
}

void StageGraph::add_stage(std::string name, std::vector<std::string> inputs,
                           std::function<std::unique_ptr<Stage>()> create) {
  if (by_name_.count(name))
    throw Error("", "stage graph", fmt::format("'{}' is declared twice", name), "internal error");
  auto n = std::make_unique<Node>();
  n->name = name;
  n->inputs = std::move(inputs);
  n->create = std::move(create);
  n->counters.name = name;
  by_name_[name] = n.get();
  nodes_.push_back(std::move(n));
}

StageGraph::Node& StageGraph::node(std::string_view name) {
  auto it = by_name_.find(name);
  if (it == by_name_.end())
    throw Error("", "stage graph", fmt::format("no input or stage named '{}'", name),
                "internal error: declare it before use");
  return *it->second;
}
const StageGraph::Node& StageGraph::node(std::string_view name) const {
  return const_cast<StageGraph*>(this)->node(name);
}

void StageGraph::visit(const std::string& name, std::vector<Node*>& order,
                       std::map<std::string, int>& mark) {
  int& m = mark[name];
  if (m == 2) return;
  if (m == 1)
    throw Error("", "stage graph", fmt::format("stage '{}' depends on itself", name),
                "internal error: the stage graph must be acyclic");
  m = 1;
  Node& n = node(name);
  for (const auto& in : n.inputs) visit(in, order, mark);
  mark[name] = 2;
  if (!n.is_input) order.push_back(&n);
}

UpdateReport StageGraph::update(std::span<const std::string> targets, Backend* timing) {
  std::vector<Node*> order;
  std::map<std::string, int> mark;
  for (const auto& t : targets) visit(t, order, mark);

  UpdateReport report;
  struct Stamp {
    Node* node;
    uint32_t begin, end;
  };
  std::vector<Stamp> stamps;
  if (timing) {
    timing->finish();
    timing->reset_timestamps();
  }
  for (Node* n : order) {
    bool stale = n->version == 0;
    for (const auto& in : n->inputs) {
      const auto it = n->seen.find(in);
      if (it == n->seen.end() || it->second != node(in).version) stale = true;
    }
    if (!stale) {
      ++n->counters.skips;
      report.skipped.push_back(n->name);
      continue;
    }
    if (!n->stage) {
      n->stage = n->create();
      n->counters.created = true;
      report.created.push_back(n->name);
    }
    const uint32_t t0 = timing ? timing->timestamp() : 0;
    n->stage->run();
    if (timing) stamps.push_back({n, t0, timing->timestamp()});
    for (const auto& in : n->inputs) n->seen[in] = node(in).version;
    n->version = ++clock_;
    ++n->counters.runs;
    report.ran.push_back(n->name);
    if (n->stage->loaded_from_cache()) {
      ++n->counters.cache_hits;
      report.cached.push_back(n->name);
    }
  }
  if (timing) {
    timing->finish();
    for (const Stamp& s : stamps) {
      const double ms = (timing->timestamp_ns(s.end) - timing->timestamp_ns(s.begin)) * 1e-6;
      s.node->counters.last_ms = ms;
      s.node->counters.total_ms += ms;
    }
  }
  return report;
}

bool StageGraph::pending(std::string_view stage, std::string_view ignored_input) const {
  const Node& n = node(stage);
  if (n.is_input) return false;
  if (n.version == 0) return true;
  for (const auto& in : n.inputs) {
    if (in == ignored_input) continue;
    const auto it = n.seen.find(in);
    if (it == n.seen.end() || it->second != node(in).version || pending(in, ignored_input))
      return true;
  }
  return false;
}

uint64_t StageGraph::version(std::string_view name) const {
  return node(name).version;
}
bool StageGraph::created(std::string_view name) const {
  return node(name).stage != nullptr;
}

std::vector<StageCounters> StageGraph::counters() const {
  std::vector<StageCounters> out;
  for (const auto& n : nodes_)
    if (!n->is_input) out.push_back(n->counters);
  return out;
}

const StageCounters& StageGraph::counters(std::string_view stage) const {
  return node(stage).counters;
}

void StageGraph::reset_counters() {
  for (auto& n : nodes_) {
    n->counters.runs = n->counters.skips = n->counters.cache_hits = 0;
    n->counters.total_ms = 0;
  }
}

std::string format_stage_stats(const std::vector<StageCounters>& counters) {
  std::string out = fmt::format("  {:<24} {:>8} {:>6} {:>8} {:>7} {:>10} {:>10}\n", "stage",
                                "created", "runs", "skipped", "cached", "last ms", "mean ms");
  for (const auto& c : counters)
    out += fmt::format("  {:<24} {:>8} {:>6} {:>8} {:>7} {:>10.3f} {:>10.3f}\n", c.name,
                       c.created ? "yes" : "never", c.runs, c.skips, c.cache_hits, c.last_ms,
                       c.runs ? c.total_ms / double(c.runs) : 0.0);
  return out;
}

}  // namespace masav::scene
