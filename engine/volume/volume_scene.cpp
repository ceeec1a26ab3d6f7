#include "engine/volume/volume_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <span>
#include <sstream>

#include "engine/core/error.h"
#include "engine/scene/camera_pose.h"
#include "engine/volume/value_histogram.h"
#include "engine/volume/volume_render.h"

namespace masav::volume {
namespace {

using scene::ParamSet;

const scene::TableSchema& source_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("source",
                         "the volume file, read as `masav volume` reads it (the same options and "
                         "the same checks)");
    s.text("path", "", "the volume file: .nrrd/.nhdr, .vti, or raw (any other name)");
    s.text("dims", "", "raw: sizes X,Y,Z (each in [2, 8192])");
    s.text("type", "", "raw: uint8, int8, uint16, int16, uint32, int32, float32, float64");
    s.text("spacing", "", "raw: voxel size X,Y,Z ('' = 1,1,1)");
    s.flag("big_endian", false, "raw: big-endian samples");
    s.text("array", "", "vti: the array to read ('' = the first)");
    return s;
  }();
  return t;
}

const scene::TableSchema& raymarch_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("raymarch", "how the volume is raymarched (as in atom-volume)");
    s.text("transfer_file", "",
           "transfer function: lines 'value r g b a' over the volume's value range ('' = blue -> "
           "green -> red)");
    add_inline_transfer_key(s);
    s.real("step_voxels", 0.5, 0.05, 4.0, "raymarch step", "voxels");
    s.choice("compositing", "front_to_back", {"front_to_back", "lerp"},
             "emission-absorption front to back, or the thesis's lerp");
    s.flag("preintegrate", false,
           "integrate the transfer function over each step (front_to_back only)");
    add_clip_shade_keys(s);
    s.real("gain", 1.0, 0.0, 16.0, "multiplies the raymarched image");
    return s;
  }();
  return t;
}

// "X,Y,Z" as numbers ("" = none); a word that is not a number is refused naming the key.
template <class T>
std::vector<T> parse_list(const std::string& text, const char* key) {
  std::vector<T> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    T v{};
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (ec != std::errc() || end != item.data() + item.size())
      throw_invalid("scene", key, text, "numbers separated by commas, X,Y,Z");
    out.push_back(v);
  }
  return out;
}

template <class T>
std::string join_list(const std::vector<T>& v) {
  std::string out;
  for (const T& x : v) out += (out.empty() ? "" : ",") + fmt::format("{}", x);
  return out;
}

class VolumeFileScene final : public scene::SceneInstance {
 public:
  VolumeFileScene(Backend& b, const ParamSet& p) : SceneInstance(b, p), render_(b) {
    validate(p);
    load();  // a file that cannot be read refuses the scene, before any frame
    add_parameter_inputs();
    auto stage = [this](const char* name, std::vector<std::string> in, std::function<void()> fn) {
      graph_.add_stage(name, std::move(in),
                       [fn] { return std::make_unique<scene::LambdaStage>(fn); });
    };
    stage("load",
          {"source.path", "source.dims", "source.type", "source.spacing", "source.big_endian",
           "source.array"},
          [this] {
            if (!loaded_fresh_) load();
            loaded_fresh_ = false;
          });
    stage("transfer", {"raymarch.transfer_file", "raymarch.transfer"},
          [this] { render_.load_transfer(transfer_points_of(params_, "raymarch")); });
    stage("bricks", {"load", "transfer"}, [this] { render_.build_bricks(desc_, volume_); });
    stage(
        "raymarch",
        {"bricks", "view", "preview", "render.width", "render.height", "raymarch.step_voxels",
         "raymarch.compositing", "raymarch.preintegrate", "raymarch.clip", "raymarch.clip_position",
         "raymarch.clip_keep", "raymarch.shade", "raymarch.shade_specular"},
        [this] { render_.raymarch(params_, "raymarch", desc_, volume_, pose(), preview_level()); });
  }

  std::vector<std::string> targets() const override { return {"raymarch"}; }
  uint32_t max_preview_level() const override { return scene::kMaxPreviewLevel; }

  std::string title() const override {
    const std::string& file_title = params_.get_text("scene.title");
    if (!file_title.empty()) return file_title;
    return fmt::format("volume {}: {}x{}x{} values in [{:.4g}, {:.4g}]", name(), desc_.dims.x,
                       desc_.dims.y, desc_.dims.z, min_, max_);
  }

  std::vector<uint32_t> value_histogram(uint32_t bins) const override {
    return volume::value_histogram(backend_.download(volume_), desc_.value_min, desc_.value_max,
                                   bins);
  }
  uint64_t volume_version() const override { return graph_.version("load"); }

  scene::SceneView view() const override {
    scene::SceneView v;
    v.box = box();
    v.background = render_.image_layer(float(params_.get_real("raymarch.gain")),
                                       fmt::format("value of {}", name()), desc_.value_min,
                                       desc_.value_max, graph_.version("raymarch"));
    return v;
  }

 protected:
  void on_clock(const scene::FrameClock& clock) override { time_s_ = clock.time_s; }

  void validate(const ParamSet& p) const override {
    VolumeFileOptions o = volume_file_options(p);
    if (o.file.empty())
      throw_invalid("scene", "source.path", "''", "a volume file (.nrrd, .nhdr, .vti or raw)");
    check_volume_file_options(o);
    check_transfer_keys(p, "raymarch");
    if (p.get_flag("raymarch.preintegrate") &&
        p.get_text("raymarch.compositing") != "front_to_back")
      throw Error("", "volume",
                  fmt::format("raymarch.preintegrate = true with raymarch.compositing = {}",
                              p.get_text("raymarch.compositing")),
                  "pre-integration needs compositing = \"front_to_back\" (lerp has no step)");
  }

 private:
  void load() {
    const ScalarVolume v = load_volume_file(volume_file_options(params_));
    desc_ = volume_desc(v);
    min_ = v.min;
    max_ = v.max;
    if (volume_.size() != v.values.size())
      volume_ = backend_.create<Real>(v.values.size(), "volume");
    backend_.upload(volume_, std::span<const float>(v.values));
    loaded_fresh_ = true;
  }

  std::string name() const {
    return std::filesystem::path(params_.get_text("source.path")).filename().string();
  }

  scene::Box box() const { return {desc_.box_min, desc_.box_max}; }
  scene::CameraPose pose() const { return scene::camera_pose(params_, box(), time_s_); }

  VolumeRender render_;
  Buffer<Real> volume_;
  VolumeDesc desc_;
  double min_ = 0, max_ = 0;  // the raw range, for the title
  bool loaded_fresh_ = false;  // read by the constructor: the first `load` stage has nothing to do
  double time_s_ = 0;
};

}  // namespace

VolumeFileOptions volume_file_options(const ParamSet& p) {
  VolumeFileOptions o;
  o.file = p.get_text("source.path");
  o.dims = parse_list<uint32_t>(p.get_text("source.dims"), "source.dims");
  o.type = p.get_text("source.type");
  o.spacing = parse_list<float>(p.get_text("source.spacing"), "source.spacing");
  o.big_endian = p.get_flag("source.big_endian");
  o.array = p.get_text("source.array");
  return o;
}

void set_volume_file_options(ParamSet& p, const VolumeFileOptions& o) {
  p.set("source.path", o.file);
  p.set("source.dims", join_list(o.dims));
  p.set("source.type", o.type);
  p.set("source.spacing", join_list(o.spacing));
  p.set("source.big_endian", o.big_endian);
  p.set("source.array", o.array);
}

scene::SceneType volume_scene_type() {
  scene::SceneType t;
  t.name = "volume";
  t.help = "a scalar volume file (raw, NRRD, VTI) raymarched through a transfer function";
  t.tables = {&source_table(), &raymarch_table()};
  t.kernels = [](const ParamSet&) {
    return std::vector<KernelId>{KernelId::volume_bricks, KernelId::volume_brick_skip,
                                 KernelId::raymarch};
  };
  // The volume kernels' checks build their own small volume (engine/atom/atom_cross_checks.cpp).
  t.check_inputs = [](const ParamSet& p) {
    scene::CheckInputs c;
    c.points = uint32_t(std::min<int64_t>(1000, p.get_int("verify.max_points")));
    c.params = p;
    return c;
  };
  t.make = [](Backend& b, const ParamSet& p, const scene::SceneHost&) {
    return std::unique_ptr<scene::SceneInstance>(std::make_unique<VolumeFileScene>(b, p));
  };
  return t;
}

}  // namespace masav::volume
