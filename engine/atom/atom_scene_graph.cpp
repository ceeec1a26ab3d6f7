#include "engine/atom/atom_scene_graph.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/atom/atom_scene.h"
#include "engine/atom/atom_schema.h"
#include "engine/atom/orbital.h"
#include "engine/core/error.h"
#include "engine/scene/camera_pose.h"
#include "engine/volume/value_histogram.h"
#include "engine/volume/volume_render.h"

namespace masav::atom {
namespace {

using scene::ParamSet;

// The scattering table stage: reports whether its table came from the disk cache.
class TableStage final : public scene::Stage {
 public:
  explicit TableStage(std::function<bool()> run) : run_(std::move(run)) {}
  void run() override { from_cache_ = run_(); }
  bool loaded_from_cache() const override { return from_cache_; }

 private:
  std::function<bool()> run_;
  bool from_cache_ = false;
};

class AtomCloudScene final : public scene::SceneInstance {
 public:
  AtomCloudScene(Backend& b, const ParamSet& p, bool volume, std::string cache_dir)
      : SceneInstance(b, p),
        volume_(volume),
        cache_dir_(std::move(cache_dir)),
        core_(b, (validate(p), options_of(p))),
        render_(b) {
    synced_ = domain_version();
    file_subject_ = subject();
    exposure_set_ = params_.get_real("nebula.exposure");
    exposure_subject_ = file_subject_;
    add_parameter_inputs();
    // The view the volume is lit for (see follow_lit_view).
    graph_.add_input("lit_view");
    auto stage = [](auto fn) { return std::make_unique<scene::LambdaStage>(fn); };
    auto add = [&](const char* name, std::vector<std::string> in, std::function<void()> fn) {
      graph_.add_stage(name, std::move(in), [this, fn, stage] {
        return stage([this, fn] {
          sync();
          fn();
        });
      });
    };
    add("cloud",
        {"atom.state", "atom.n", "atom.l", "atom.m", "atom.orbital", "atom.count", "atom.placement",
         "atom.seed"},
        [this] { core_.build_cloud(); });
    add("density", {"cloud", "nebula.density_dims", "nebula.box_probability"},
        [this] { core_.build_density(); });
    graph_.add_stage(
        "scatter_table",
        {"scatter.rows", "scatter.bins", "scatter.tau_step", "scatter.g", "scatter.albedo",
         "scatter.photons", "scatter.max_scatterings", "scatter.seed"},
        [this] {
          return std::make_unique<TableStage>([this] {
            sync();
            core_.build_table();
            return core_.times().table_from_cache;
          });
        });
    add("illuminate",
        {"density", "nebula.tau_peak", "nebula.path", "nebula.step_a0", "scatter.albedo"},
        [this] { core_.illuminate(); });
    add("viewer", {"illuminate", "scatter_table", volume_ ? "lit_view" : "view"}, [this] {
      core_.set_viewer(pose().eye);
      core_.view();
    });
    add("light", {"viewer", "nebula.power_lm", "nebula.exposure"}, [this] { rescale(); });
    if (!volume_) return;
    add("voxelize", {"light", "volume.dims", "volume.s", "volume.t"},
        [this] { core_.voxelize(light_to_unit_); });
    add("transfer", {"volume.transfer_file", "volume.transfer"},
        [this] { render_.load_transfer(volume::transfer_points_of(params_, "volume")); });
    add("bricks", {"voxelize", "transfer"},
        [this] { render_.build_bricks(core_.volume(), core_.sample); });
    add("raymarch",
        {"bricks", "view", "preview", "render.width", "render.height", "volume.step_voxels",
         "volume.compositing", "volume.preintegrate", "volume.clip", "volume.clip_position",
         "volume.clip_keep", "volume.shade", "volume.shade_specular"},
        [this] {
          render_.raymarch(params_, "volume", core_.volume(), core_.sample, pose(),
                           preview_level());
        });
  }

  std::vector<uint32_t> value_histogram(uint32_t bins) const override {
    if (!volume_ || graph_.version("voxelize") == 0) return {};
    const VolumeDesc d = core_.volume();
    return volume::value_histogram(backend_.download(core_.sample), d.value_min, d.value_max, bins);
  }
  uint64_t volume_version() const override { return volume_ ? graph_.version("voxelize") : 0; }

  uint32_t max_preview_level() const override { return volume_ ? scene::kMaxPreviewLevel : 0; }

  std::vector<std::string> targets() const override {
    if (!volume_) return {"light"};
    std::vector<std::string> t = {"raymarch"};
    if (params_.get_flag("volume.show_particles")) t.push_back("light");
    return t;
  }

  scene::ParamSet saved_params() const override {
    scene::ParamSet p = params_;
    if (!exposure_applies()) p.set("nebula.exposure", 0.0);
    return p;
  }

  std::string title() const override {
    const std::string& file_title = params_.get_text("scene.title");
    if (!file_title.empty() && subject() == file_subject_) return file_title;
    return fmt::format("hydrogen {}{}: {}", params_.get_text("atom.state"),
                       volume_ ? " as a volume" : "", atom::describe(state_of(params_)));
  }

  scene::SceneView view() const override {
    scene::SceneView v;
    v.box = box();
    if ((!volume_ || params_.get_flag("volume.show_particles")) && core_.light.valid() &&
        graph_.version("light") > 0) {
      scene::PointLayer pl;
      pl.positions = &core_.positions;
      pl.count = uint32_t(core_.positions.size());
      pl.from = scene::PointLayer::ScalarFrom::buffer;
      pl.scalar = &core_.light.impl();
      // The rescale: light * light_to_unit = 1 is the colour map's top. The buffer holds the
      // light at the reference power; the legend shows it at the current one.
      pl.scalar_lo = 0;
      pl.scalar_hi = float(1.0 / std::max(double(light_to_unit_), 1e-30));
      pl.shown_per_unit = float(params_.get_real("nebula.power_lm") / kReferencePowerLm);
      pl.scalar_name =
          fmt::format("light at {:.0f}K lm (cd/a0^2)", params_.get_real("nebula.power_lm") / 1e3);
      pl.scalar_key = "light";
      pl.version = graph_.version("viewer");
      v.points = pl;
    }
    if (volume_)
      v.background = render_.image_layer(float(params_.get_real("volume.gain")),
                                         "volume sample s*g + t*p (1 = light at full colour)", 0.0f,
                                         1.0f, graph_.version("raymarch"));
    return v;
  }

 protected:
  void on_clock(const scene::FrameClock& clock) override {
    time_s_ = clock.time_s;
    follow_lit_view();
  }

  void validate(const ParamSet& p) const override {
    (void)state_of(p);  // a custom state must be a hydrogen state
    const uint64_t limit = backend_.caps().max_buffer_bytes;
    const uint64_t count = uint64_t(p.get_int("atom.count"));
    if (limit && count * 4 * backend_.real_bytes() > limit)
      throw_invalid("scene", "atom.count", std::to_string(count),
                    fmt::format("at most {} on {} (one buffer holds {} MiB)",
                                limit / (4 * backend_.real_bytes()), backend_.caps().device_name,
                                limit >> 20));
    if (p.has_table("volume")) {
      volume::check_transfer_keys(p, "volume");
      const double s = p.get_real("volume.s"), t = p.get_real("volume.t");
      if (s + t <= 0)
        throw Error("", "atom-volume",
                    fmt::format("volume.s = {} and volume.t = {} leave the volume empty", s, t),
                    "give s or t a positive weight (the thesis: s = 0.6, t = 0.4)");
      if (p.get_flag("volume.preintegrate") && p.get_text("volume.compositing") != "front_to_back")
        throw Error("", "atom-volume",
                    fmt::format("volume.preintegrate = true with volume.compositing = {}",
                                p.get_text("volume.compositing")),
                    "pre-integration needs compositing = \"front_to_back\" (lerp has no step)");
    }
  }

 private:
  // Brings the pipeline's options to the current parameters (the derived grids follow).
  // Only the domain's own tables feed the pipeline: a camera or render change (every frame of
  // an orbit) does not redo the box and optical-depth set-up.
  void sync() {
    const uint64_t v = domain_version();
    if (synced_ == v) return;
    core_.reconfigure(options_of(params_));
    synced_ = v;
  }

  // The volume's light depends on the view (the phase function towards the viewer), and
  // relighting and voxelizing the cloud costs as much as a preview's raymarch: while the demo
  // previews a moving view, the volume keeps the light of the last view it was lit for; the full
  // level relights it for the current view, so a still frame is the one-shot frame.
  void follow_lit_view() {
    if (!volume_ || preview_level() > 0) return;
    const uint64_t view = graph_.version("view");
    if (view == lit_view_) return;
    graph_.touch("lit_view");
    lit_view_ = view;
  }

  // Whether nebula.exposure sets the scale: it is set, and for the state shown -- set since
  // rescale() last looked, or while this state showed.
  bool exposure_applies() const {
    const double set = params_.get_real("nebula.exposure");
    return set > 0 && (set != exposure_set_ || subject() == exposure_subject_);
  }

  // The state shown, as the overlay's title names it.
  std::string subject() const {
    return params_.get_text("atom.state") + " " + atom::describe(state_of(params_));
  }

  uint64_t domain_version() const {
    uint64_t v = 0;
    for (const scene::TableSchema* t : params_.tables()) {
      const std::string& name = t->name();
      if (name != "atom" && name != "nebula" && name != "scatter" && name != "volume") continue;
      for (const scene::ParamSpec& spec : t->params())
        v = std::max(v, params_.version(name + "." + spec.key));
    }
    return v;
  }

  scene::Box box() const {
    const float h = float(core_.box_half_width());
    return {{-h, -h, -h}, {h, h, h}};
  }

  scene::CameraPose pose() const { return scene::camera_pose(params_, box(), time_s_); }

  void rescale() {
    // A fixed scale (the file's, or the state's own): never the light of the current view, so
    // the colours mean the same in every view and on every backend. An exposure belongs to the
    // state it was set for (a scene file's to the file's state): another state shown takes its
    // own scale until an exposure is set for it.
    const double set = params_.get_real("nebula.exposure");
    if (set != exposure_set_) {
      exposure_set_ = set;
      exposure_subject_ = subject();
    }
    const double exposure = exposure_applies() ? set : 1.0 / core_.full_colour_light();
    light_to_unit_ = float(exposure * params_.get_real("nebula.power_lm") / kReferencePowerLm);
  }

  // The pipeline's options: the parameters', and the program's cache directory.
  AtomSceneOptions options_of(const ParamSet& p) const {
    AtomSceneOptions o = scene_options_of(p);
    o.cache_dir = cache_dir_;
    return o;
  }

  bool volume_;
  std::string cache_dir_;  // declared before core_, which its constructor reads it for
  AtomScene core_;
  uint64_t synced_ = 0;
  std::string file_subject_;      // subject() as the scene was created
  double exposure_set_ = 0;       // nebula.exposure as rescale() last saw it
  std::string exposure_subject_;  // subject() when nebula.exposure was set
  double time_s_ = 0;
  uint64_t lit_view_ = 0;  // the version of "view" the volume was last lit for
  float light_to_unit_ = 1;
  volume::VolumeRender render_;
};

}  // namespace

std::unique_ptr<scene::SceneInstance> make_atom_scene(Backend& b, const scene::ParamSet& p,
                                                      bool volume, const std::string& cache_dir) {
  return std::make_unique<AtomCloudScene>(b, p, volume, cache_dir);
}

}  // namespace masav::atom
