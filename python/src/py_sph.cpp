// masav.Sph: the SPH simulation and its run object, as `masav sph` drives them. A run goes
// through SphRun (engine/sph/sph_run.h) with the command line's defaults (8 steps per block, no
// progress events: `masav sph -q`), so its CSV, snapshots and checkpoints are the command line's,
// byte for byte on the CPU backend. The state: download() copies it by particle id from any
// backend; on the CPU reference positions, velocities, density, pressure and ids are numpy
// views of the simulation's own arrays (storage order, that of the last grid rebuild).
// Ctrl-C is polled between blocks: the run stops at a whole step, writes its checkpoint if it
// has a directory, and raises KeyboardInterrupt with the simulation usable.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "engine/io/writable_paths.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_run.h"
#include "engine/sph/sph_scene_options.h"
#include "engine/sph/sph_simulation.h"
#include "python/src/py_arrays.h"
#include "python/src/py_casters.h"

namespace masav::python {
namespace {

// The simulation with the backend it runs on (which must outlive it).
struct PySph {
  BackendRef backend;
  std::unique_ptr<SphSimulation> sim;
};

// The overrides masav.Sph takes, as `masav sph` names them (without the dashes).
using SceneOptions = SphSceneOptions;

SphScene scene_from(const SceneOptions& o) {
  return make_sph_scene(o, "masav.Sph");
}

std::unique_ptr<PySph> make_sim(BackendRef b, const SphScene& scene, uint32_t block_steps) {
  if (block_steps < 1 || block_steps > SphSimulation::kMaxBlockSteps)
    bad_argument("masav.Sph", "block_steps", std::to_string(block_steps),
                 fmt::format("from 1 to {}", SphSimulation::kMaxBlockSteps));
  auto s = std::make_unique<PySph>();
  s->backend = std::move(b);
  s->sim = without_gil(*s->backend, [&](Backend& be) {
    auto sim = std::make_unique<SphSimulation>(be, scene);
    sim->set_block_steps(block_steps);
    return sim;
  });
  return s;
}

std::unique_ptr<PySph> create(BackendRef b, SceneOptions o, uint32_t block_steps) {
  return make_sim(std::move(b), scene_from(o), block_steps);
}

std::unique_ptr<PySph> restore(BackendRef b, const std::string& dir, uint32_t block_steps) {
  const std::string path = SphRun::checkpoint_path(dir);
  SphCheckpoint c = read_sph_checkpoint(path);
  auto s = make_sim(std::move(b), c.scene, block_steps);
  without_gil(*s->backend, [&](Backend&) { restore_sph_checkpoint(*s->sim, c, path); });
  return s;
}

// Whether Ctrl-C (or another signal with a Python handler) arrived: its exception stays set,
// for the caller to raise once the run has stopped at a whole step.
bool signalled() {
  py::gil_scoped_acquire gil;
  return PyErr_CheckSignals() != 0;
}

struct RunArgs {
  std::optional<uint64_t> steps;
  std::optional<double> t_end;
  std::string csv, out_dir, checkpoint_dir;
  uint64_t diag_every = 1, vtp_every = 0, checkpoint_every = 0;
  bool overwrite = false;
};

py::dict run(PySph& s, const RunArgs& a) {
  if (a.steps.has_value() == a.t_end.has_value())
    bad_argument("Sph.run", "steps/t_end", a.steps ? "both" : "neither",
                 "exactly one: a step count or an end time (s)");
  SphRunOptions o;
  if (a.steps) {
    if (*a.steps == 0) bad_argument("Sph.run", "steps", "0", "at least 1");
    o.steps = *a.steps;
  } else {
    if (!(*a.t_end > 0) || !std::isfinite(*a.t_end))
      bad_argument("Sph.run", "t_end", fmt::format("{}", *a.t_end), "a time > 0 (s)");
    o.t_end = *a.t_end;
  }
  if (a.diag_every == 0) bad_argument("Sph.run", "diag_every", "0", "at least 1");
  o.csv = a.csv;
  o.diag_every = a.diag_every;
  o.out_dir = a.out_dir;
  o.name = s.sim->scene().preset == "dam-break" ? "dambreak" : s.sim->scene().preset;
  o.vtp_every = a.vtp_every;
  o.checkpoint_dir = a.checkpoint_dir;
  o.checkpoint_every = a.checkpoint_every;
  o.overwrite = a.overwrite;
  if (o.checkpoint_every && o.checkpoint_dir.empty())
    bad_argument("Sph.run", "checkpoint_every", std::to_string(o.checkpoint_every),
                 "0 without a checkpoint_dir");
  o.progress_every = 0;
  SphRunResult r = without_gil(*s.backend, [&](Backend&) {
    SphRun run(o, nullptr);
    SphRunEvents events;
    events.interrupted = &signalled;
    return run.run(*s.sim, events);
  });
  if (r.interrupted) throw py::error_already_set();  // the KeyboardInterrupt signalled() left
  if (r.error) {
    const std::string where =
        r.last_good.empty()
            ? ""
            : fmt::format("the last good state (step {}) is in {}", s.sim->steps(), r.last_good);
    throw Error("", "", *r.error, where);
  }
  py::dict d;
  d["steps"] = r.steps;
  d["substeps"] = r.substeps;
  d["wall_s"] = r.wall_s;
  d["csv_rows"] = r.csv_rows;
  d["final_checkpoint"] = r.final_checkpoint;
  return d;
}

py::array state_array(const std::vector<Vec4d>& v) {
  py::array_t<double> a({py::ssize_t(v.size()), py::ssize_t(4)});
  std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(Vec4d));
  return a;
}

py::dict download(PySph& s) {
  const SphState st = without_gil(*s.backend, [&](Backend&) { return s.sim->download(); });
  py::dict d;
  d["positions"] = state_array(st.positions);
  d["velocities"] = state_array(st.velocities);
  d["density"] = py::array_t<double>(py::ssize_t(st.density.size()), st.density.data());
  d["pressure"] = py::array_t<double>(py::ssize_t(st.pressure.size()), st.pressure.data());
  d["neighbors"] = py::array_t<double>(py::ssize_t(st.neighbors.size()), st.neighbors.data());
  return d;
}

// One of the committed state's buffers, borrowed (it follows the simulation's buffer).
template <class T>
std::unique_ptr<PyBuffer> state_buffer(py::object self,
                                       const Buffer<T>& (SphSimulation::*get)() const) {
  PySph& s = self.cast<PySph&>();
  auto& b = const_cast<Buffer<T>&>(((*s.sim).*get)());
  return std::make_unique<PyBuffer>(s.backend, elem_kind_of<T>(), &b, self);
}

template <class T>
py::array state_view(py::object self, const Buffer<T>& (SphSimulation::*get)() const) {
  auto b = state_buffer(self, get);
  return host_view(*b, self);
}

std::unique_ptr<PyBuffer> buffer_named(py::object self, const std::string& name) {
  if (name == "positions") return state_buffer(self, &SphSimulation::positions);
  if (name == "velocities") return state_buffer(self, &SphSimulation::velocities);
  if (name == "density") return state_buffer(self, &SphSimulation::density);
  if (name == "pressure") return state_buffer(self, &SphSimulation::pressure);
  if (name == "ids") return state_buffer(self, &SphSimulation::ids);
  bad_argument("Sph.buffer", "name", name, "positions, velocities, density, pressure or ids");
}

}  // namespace

void bind_sph(py::module_& m) {
  m.def(
      "sph_presets",
      [] {
        std::vector<std::pair<std::string, std::string>> out;
        for (const auto& p : sph_presets())
          out.emplace_back(p.name == "dam-break" ? "dambreak" : p.name, p.description);
        return out;
      },
      "The SPH presets: (name, description).");

  py::class_<PySph>(m, "Sph",
                    "An SPH simulation on one backend, built as `masav sph` builds it from the "
                    "same options.")
      .def(py::init([](BackendRef b, std::string preset, uint32_t particles,
                       std::optional<std::string> integrator, std::optional<std::string> pressure,
                       std::optional<double> dt, std::optional<std::string> cfl_guard,
                       std::optional<double> viscosity, std::optional<double> sound_speed,
                       std::optional<double> max_compression, std::optional<double> kp,
                       std::optional<double> smoothing_radius, std::optional<double> restitution,
                       std::optional<uint64_t> seed, uint32_t block_steps) {
             SceneOptions o{std::move(preset),
                            particles,
                            integrator,
                            pressure,
                            cfl_guard,
                            dt,
                            viscosity,
                            sound_speed,
                            max_compression,
                            kp,
                            smoothing_radius,
                            restitution,
                            seed};
             return create(std::move(b), o, block_steps);
           }),
           py::arg("backend"), py::arg("preset") = "water", py::arg("particles") = 32768,
           py::arg("integrator") = py::none(), py::arg("pressure") = py::none(),
           py::arg("dt") = py::none(), py::arg("cfl_guard") = py::none(),
           py::arg("viscosity") = py::none(), py::arg("sound_speed") = py::none(),
           py::arg("max_compression") = py::none(), py::arg("kp") = py::none(),
           py::arg("smoothing_radius") = py::none(), py::arg("restitution") = py::none(),
           py::arg("seed") = py::none(), py::arg("block_steps") = 8,
           "The options of `masav sph` (preset, particles, integrator, pressure, dt, ...), "
           "checked as it checks them.")
      .def_static("restore", &restore, py::arg("backend"), py::arg("checkpoint_dir"),
                  py::arg("block_steps") = 8,
                  "The simulation a checkpoint directory holds (`masav sph --restart DIR`): "
                  "its scene, state and time stepping.")
      .def(
          "step", [](PySph& s) { without_gil(*s.backend, [&](Backend&) { s.sim->step(); }); },
          "One step (the CFL guard may split it into sub-steps).")
      .def(
          "run",
          [](PySph& s, std::optional<uint64_t> steps, std::optional<double> t_end, std::string csv,
             uint64_t diag_every, std::string out_dir, uint64_t vtp_every,
             std::string checkpoint_dir, uint64_t checkpoint_every, bool overwrite) {
            return run(s, {steps, t_end, std::move(csv), std::move(out_dir),
                           std::move(checkpoint_dir), diag_every, vtp_every, checkpoint_every,
                           overwrite});
          },
          py::arg("steps") = py::none(), py::arg("t_end") = py::none(), py::arg("csv") = "",
          py::arg("diag_every") = 1, py::arg("out_dir") = "", py::arg("vtp_every") = 0,
          py::arg("checkpoint_dir") = "", py::arg("checkpoint_every") = 0,
          py::arg("overwrite") = false,
          "Further `steps`, or until the simulated time t_end (s), with the outputs of `masav "
          "sph` (csv, out_dir + vtp_every, checkpoint_dir + checkpoint_every). An out_dir holding "
          "an earlier run's snapshots is refused unless overwrite=True, which removes only those. "
          "Ctrl-C stops it at a whole step and raises KeyboardInterrupt.")
      .def(
          "checkpoint",
          [](PySph& s, const std::string& dir) {
            const std::string path = SphRun::checkpoint_path(dir);
            without_gil(*s.backend, [&](Backend&) {
              ensure_writable_dir(dir, "checkpoint_dir");  // made if missing, as a run makes it
              write_sph_checkpoint(path, *s.sim);
            });
            return path;
          },
          py::arg("checkpoint_dir"),
          "Writes DIR/checkpoint.masav, which Sph.restore and `masav sph --restart DIR` resume.")
      .def("download", &download,
           "The state by particle id (copies, from any backend): positions and velocities (n, 4), "
           "density, pressure, neighbors (n,).")
      .def("buffer", &buffer_named, py::arg("name"),
           "A state buffer (positions, velocities, density, pressure, ids) as a masav.Buffer that "
           "follows the simulation: for kernels, DLPack or __cuda_array_interface__.")
      .def_property_readonly(
          "positions", [](py::object self) { return state_view(self, &SphSimulation::positions); },
          "CPU backend: a view (n, 4) of the positions (m; w = inverse mass scale), in storage "
          "order (see ids), valid until the next step.")
      .def_property_readonly(
          "velocities",
          [](py::object self) { return state_view(self, &SphSimulation::velocities); })
      .def_property_readonly(
          "density", [](py::object self) { return state_view(self, &SphSimulation::density); })
      .def_property_readonly(
          "pressure", [](py::object self) { return state_view(self, &SphSimulation::pressure); })
      .def_property_readonly(
          "ids", [](py::object self) { return state_view(self, &SphSimulation::ids); },
          "The particle id of each element of the views.")
      .def(
          "set_velocities",
          [](PySph& s, const py::array& v) {
            const size_t n =
                checked_elements(v, ElemKind::real4, "Sph.set_velocities", true, false);
            if (n != s.sim->particle_count())
              bad_argument("Sph.set_velocities", "n", std::to_string(n),
                           fmt::format("the {} particles", s.sim->particle_count()));
            auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
            std::vector<Vec4d> by_id(n);
            std::memcpy(static_cast<void*>(by_id.data()), d.data(), n * sizeof(Vec4d));
            without_gil(*s.backend, [&](Backend&) { s.sim->set_velocities(by_id); });
          },
          py::arg("velocities"), "Replaces the velocities, (n, 4) by particle id.")
      .def_property_readonly("time", [](PySph& s) { return s.sim->time(); })
      .def_property_readonly("steps", [](PySph& s) { return s.sim->steps(); })
      .def_property_readonly("substeps", [](PySph& s) { return s.sim->substeps(); })
      .def_property_readonly("retries", [](PySph& s) { return s.sim->retries(); })
      .def_property_readonly("last_dt", [](PySph& s) { return s.sim->last_dt(); })
      .def_property_readonly("particle_count", [](PySph& s) { return s.sim->particle_count(); })
      .def_property_readonly("backend", [](PySph& s) { return s.backend; })
      .def_property_readonly("layout",
                             [](PySph& s) {
                               const SphParticles& l = s.sim->layout();
                               py::dict d;
                               d["fluid"] = l.fluid;
                               d["obstacle"] = l.obstacle;
                               d["dx"] = l.dx;
                               d["h"] = l.h;
                               d["mass"] = l.mass;
                               return d;
                             })
      .def("__repr__", [](PySph& s) {
        const SphScene& sc = s.sim->scene();
        return fmt::format("masav.Sph('{}', {} particles, {} / {}, step {}, t = {:.6g} s on {})",
                           sc.preset, s.sim->particle_count(), to_string(sc.model),
                           to_string(sc.integrator), s.sim->steps(), s.sim->time(),
                           s.backend->backend->name());
      });
}

}  // namespace masav::python
