// Volumes from Python: a scalar volume raymarched to an (H, W, 4) image as `masav volume` does it
// (the same camera presets, step and compositing), volume files read as `masav volume` reads
// them, and transfer functions as (256, 4) RGBA tables.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>

#include "engine/volume/transfer_function.h"
#include "engine/volume/volume_file.h"
#include "masav/volume.h"
#include "python/src/py_arrays.h"
#include "python/src/py_casters.h"

namespace masav::python {
namespace {

// A (Z, Y, X) array of float32 or float64, finite, each axis 2 to 8192 samples (the volume
// files' bounds), as the engine's volume (x fastest).
volume::ScalarVolume volume_of(const py::array& a, Vec3f origin, Vec3f spacing) {
  const char* what = "masav.raymarch volume";
  const char kind = a.dtype().kind();
  if (kind != 'f')
    bad_argument(what, "dtype", py::str(a.dtype()).cast<std::string>(), "float32 or float64");
  if (a.ndim() != 3)
    bad_argument(what, "ndim", std::to_string(a.ndim()), "3: an array (Z, Y, X), x fastest");
  for (int d = 0; d < 3; ++d)
    if (a.shape(d) < 2 || a.shape(d) > 8192)
      bad_argument(what, fmt::format("shape[{}]", d), std::to_string(a.shape(d)),
                   "from 2 to 8192 samples");
  // Read as double, so a float64 array keeps its range (1e-300, beyond FLT_MAX) until the engine
  // normalises it.
  auto f = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  volume::ScalarVolume v;
  v.dims = {uint32_t(a.shape(2)), uint32_t(a.shape(1)), uint32_t(a.shape(0))};
  v.origin = origin;
  v.spacing = spacing;
  for (size_t i = 0; i < size_t(f.size()); ++i)
    if (!std::isfinite(f.data()[i]))
      bad_argument(what, "value", fmt::format("element {} is {}", i, f.data()[i]),
                   "finite (no NaN or infinity)");
  volume::set_samples(v, std::span<const double>(f.data(), size_t(f.size())), what);
  return v;
}

// An (N, 4) RGBA table in [0, 1], or the default transfer function.
std::vector<Vec4d> transfer_of(const std::optional<py::array>& t) {
  if (!t) return volume::resample_transfer(volume::default_transfer_points());
  const size_t n = checked_elements(*t, ElemKind::real4, "masav.raymarch transfer", true, false);
  if (n < 2 || n > 4096)
    bad_argument("masav.raymarch transfer", "n", std::to_string(n), "from 2 to 4096 entries");
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(*t);
  std::vector<Vec4d> tf(n);
  std::memcpy(static_cast<void*>(tf.data()), d.data(), n * sizeof(Vec4d));
  for (size_t i = 0; i < 4 * n; ++i)
    if (d.data()[i] < 0 || d.data()[i] > 1)
      bad_argument("masav.raymarch transfer", "value",
                   fmt::format("element ({}, {}) is {}", i / 4, i % 4, d.data()[i]), "in [0, 1]");
  return tf;
}

py::array table_array(const std::vector<Vec4d>& tf) {
  py::array_t<double> a({py::ssize_t(tf.size()), py::ssize_t(4)});
  std::memcpy(a.mutable_data(), tf.data(), tf.size() * sizeof(Vec4d));
  return a;
}

py::array raymarch(const BackendRef& b, const py::array& values, uint32_t width, uint32_t height,
                   const std::string& view, const std::optional<py::array>& tf_in,
                   float step_voxels, const std::string& mode, bool preintegrate, Vec3f origin,
                   Vec3f spacing, const std::optional<RaymarchParams>& params) {
  const volume::ScalarVolume vol = volume_of(values, origin, spacing);
  if (mode != "front_to_back" && mode != "lerp")
    bad_argument("masav.raymarch", "mode", mode, "front_to_back or lerp");
  RaymarchOptions o;
  o.width = width;
  o.height = height;
  o.view = view;
  o.step_voxels = step_voxels;
  o.lerp = mode == "lerp";
  o.preintegrate = preintegrate;
  if (tf_in) o.transfer = transfer_of(tf_in);  // else masav volume's default
  const Image img = without_gil(*b, [&](Backend& be) {
    return params ? masav::raymarch(be, vol, *params, o.transfer) : masav::raymarch(be, vol, o);
  });
  py::array_t<double> out({py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(4)});
  std::memcpy(out.mutable_data(), img.pixels.data(), img.pixels.size() * sizeof(Vec4d));
  return out;
}

}  // namespace

void bind_volume(py::module_& m) {
  m.def("raymarch", &raymarch, py::arg("backend"), py::arg("volume"), py::arg("width") = 256,
        py::arg("height") = 256, py::arg("view") = "front", py::arg("transfer") = py::none(),
        py::arg("step_voxels") = 0.5f, py::arg("mode") = "front_to_back",
        py::arg("preintegrate") = false, py::arg("origin") = Vec3f{0, 0, 0},
        py::arg("spacing") = Vec3f{1, 1, 1}, py::arg("params") = py::none(),
        "Raymarches `volume` (Z, Y, X) as `masav volume` does: the camera of `view` (front, "
        "top, left), step_voxels per sample, the transfer function `transfer` (N, 4) RGBA or "
        "the default; `params` (RaymarchParams) replaces the camera and knobs. Returns the "
        "image (height, width, 4): premultiplied RGBA, top row first.");
  m.def(
      "load_volume",
      [](const std::string& file, std::vector<uint32_t> dims, std::string type,
         std::vector<float> spacing, bool big_endian, std::string array) {
        volume::VolumeFileOptions o{
            file,       std::move(dims), std::move(type), std::move(spacing),
            big_endian, std::move(array)};
        const volume::ScalarVolume v = [&] {
          py::gil_scoped_release nogil;
          return volume::load_volume_file(o);
        }();
        py::array_t<float> a({py::ssize_t(v.dims.z), py::ssize_t(v.dims.y), py::ssize_t(v.dims.x)});
        std::memcpy(a.mutable_data(), v.values.data(), v.values.size() * sizeof(float));
        py::dict info;
        info["origin"] = py::cast(v.origin);
        info["spacing"] = py::cast(v.spacing);
        info["min"] = v.min;
        info["max"] = v.max;
        info["normalised"] = v.normalised;
        return py::make_tuple(a, info);
      },
      py::arg("file"), py::arg("dims") = std::vector<uint32_t>{}, py::arg("type") = "",
      py::arg("spacing") = std::vector<float>{}, py::arg("big_endian") = false,
      py::arg("array") = "",
      "Reads a volume file as `masav volume` does (.nrrd/.nhdr, .vti, or raw with dims and "
      "type): returns (values (Z, Y, X) float32, {origin, spacing, min, max, normalised}); "
      "normalised: the values are (raw - min) / (max - min), a range float32 cannot hold.");
  m.def(
      "transfer_function",
      [](const std::string& file, uint32_t size) {
        if (size < 2 || size > 4096)
          bad_argument("masav.transfer_function", "size", std::to_string(size), "2 to 4096");
        return table_array(volume::resample_transfer(
            file.empty() ? volume::default_transfer_points() : volume::load_transfer_points(file),
            size));
      },
      py::arg("file") = "", py::arg("size") = 256,
      "The transfer function of a file of `value r g b a` lines (\"\": the default) as a "
      "(size, 4) RGBA table.");
}

}  // namespace masav::python
