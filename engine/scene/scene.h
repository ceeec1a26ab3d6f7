#pragma once
// A running scene on one backend, and the registry of scene types. A scene type declares its
// parameter tables, the kernels it uses (for the cross-check), and how to build its stage graph;
// adding a scene (atom, atom-volume, sph) is one SceneType in scene_types.cpp.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/scene/param_schema.h"
#include "engine/scene/scene_view.h"
#include "engine/scene/stage_graph.h"

namespace masav::scene {

// The clock of one frame. Time-driven scenes (particles) read time_s; stepped scenes (SPH)
// step by dt_s unless paused. `step_once` advances one step while paused.
struct FrameClock {
  uint64_t frame = 0;
  double time_s = 0;
  double dt_s = 1.0 / 30;
  bool paused = false;
  bool step_once = false;
};

// The coarsest preview level a scene offers (1/16 of the width and height; see
// SceneInstance::set_preview_level): on lavapipe (a 2-core VM) a full 800x720 raymarch of the
// atom volume takes seconds, 1/8 of it still about 70 ms.
constexpr uint32_t kMaxPreviewLevel = 4;

class SceneInstance {
 public:
  SceneInstance(Backend& backend, ParamSet params);
  virtual ~SceneInstance() = default;

  Backend& backend() { return backend_; }
  const ParamSet& params() const { return params_; }
  StageGraph& graph() { return graph_; }
  const StageGraph& graph() const { return graph_; }

  // Changes a parameter (validated) and marks the stages that read it stale. Returns whether the
  // value changed. Cross-parameter limits are checked too (validate()); on failure the old value
  // stays.
  bool set(std::string_view path, const ParamValue& v);
  bool set_from_string(std::string_view path, std::string_view text);

  // Brings the stages the current parameters need up to date for this frame.
  UpdateReport update(const FrameClock& clock, bool time_stages = false);
  virtual SceneView view() const = 0;
  // Stage names update() brings up to date with the current parameters.
  virtual std::vector<std::string> targets() const = 0;
  // The time inside a stepped simulation (SPH), which is not the frame clock: a frame advances
  // it by the steps it ran, each of an adaptive dt. None for scenes that follow the frame clock.
  virtual std::optional<double> simulated_time_s() const { return std::nullopt; }
  // The overlay's title: scene.title while the scene shows what its file set up; a title made
  // from the parameters once one that names the subject (a state, a preset) has changed.
  virtual std::string title() const;
  // The parameters that reproduce what the scene shows, for saving it as a scene file: params()
  // unless a scene resolves one of them otherwise (the atom scenes: an exposure that belonged to
  // another state is written as 0, the shown state's own scale).
  virtual ParamSet saved_params() const { return params_; }

  // Scenes that raymarch a scalar volume (the demo's transfer function editor): the histogram
  // of its values over the range raymarch maps to [0, 1], in `bins` counts (empty: no volume),
  // and a number that changes whenever the volume does (0: none yet), so that a caller
  // recomputes the histogram only then.
  virtual std::vector<uint32_t> value_histogram(uint32_t bins) const {
    (void)bins;
    return {};
  }
  virtual uint64_t volume_version() const { return 0; }

  // Progressive rendering (the demo): at preview level L the scene's raymarched image is drawn
  // at 1/2^L of render.width and render.height and upsampled when shown; level 0 is the full
  // image. Scenes without such an image have no levels (max_preview_level() = 0).
  virtual uint32_t max_preview_level() const { return 0; }
  // Clamped to max_preview_level(); a change marks the input "preview" changed.
  void set_preview_level(uint32_t level);
  uint32_t preview_level() const { return preview_level_; }
  // Whether update() at `clock` would rerun a target stage for anything but the preview level:
  // the orbit camera turning with the clock, a parameter set, a stage never run.
  bool changes_pending(const FrameClock& clock) const;

 protected:
  // Called before update(): advance stepped state, touch "time" inputs, ...
  virtual void on_clock(const FrameClock& clock) = 0;
  // Cross-parameter checks (throws masav::Error naming the parameters and the remedy).
  virtual void validate(const ParamSet& p) const { (void)p; }
  // Adds every parameter of the scene's tables as a graph input, and the input "view", which
  // changes whenever the camera does (a camera.* parameter, or the time while the orbit camera
  // turns): the stages that depend on the viewpoint (viewer attenuation, the raymarch) read
  // "view" and nothing else reruns when the user looks around. Also the input "preview" (the
  // preview level), read by the stage that draws at that level.
  void add_parameter_inputs();

  Backend& backend_;
  ParamSet params_;
  StageGraph graph_;

 private:
  // Whether the orbit camera's view changes when the clock moves to time_s.
  bool view_moves_at(double time_s) const;

  double view_time_s_ = 0;
  uint32_t preview_level_ = 0;
};

// What `masav verify` and the pre-render check need from a scene (see cross_check.h).
struct CheckInputs {
  uint32_t points = 0;  // points in each kernel's check input
  uint64_t seed = 1;
  std::optional<GridParams> grid;  // the scene's hash grid (with n = points), if it has one
  float neighbor_radius = 0;
  // The scene's parameters, for checks that build their inputs from their domain's tables
  // (the atom checks read the state, the scattering table and the grids).
  ParamSet params;
};

// What a scene takes from the program that runs it, beside its parameters (the library never
// reads the process environment: the masav command line resolves these from it).
struct SceneHost {
  // The disk caches' directory (engine/util/cache_dir.h: the atom scenes keep their scattering
  // table under scatter/); "" = no cache: each run recomputes.
  std::string cache_dir;
};

struct SceneType {
  std::string name;
  std::string help;
  std::vector<const TableSchema*> tables;  // the domain's tables (the common ones are added)
  // Kernels the scene runs with these parameters (each must have a cross-check).
  std::function<std::vector<KernelId>(const ParamSet&)> kernels;
  std::function<CheckInputs(const ParamSet&)> check_inputs;
  std::function<std::unique_ptr<SceneInstance>(Backend&, const ParamSet&, const SceneHost&)> make;
  // make(), with no cache unless `host` names one.
  std::unique_ptr<SceneInstance> create(Backend& b, const ParamSet& p,
                                        const SceneHost& host = {}) const {
    return make(b, p, host);
  }
  // Optional: when a backend refuses a buffer over `limit_bytes` (LimitError), the setting of
  // these parameters that fits ("set particles.grid_cells <= 64 ..."), or "" if none is the cause.
  std::function<std::string(const ParamSet&, uint64_t limit_bytes)> fit_advice;
};

}  // namespace masav::scene
