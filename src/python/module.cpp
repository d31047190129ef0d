// module.cpp - the Python module `flowform` (pybind11): load a scene from a
// file or a dict, step and run, change the target, the region and the
// parameters at any time, read the fluid, the control particles and the
// metrics as NumPy arrays, export frames and write or resume checkpoints.
// Every ff::Error becomes flowform.Error (a RuntimeError) with the same message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/resource_limits.h"
#include "host/backend_factory.h"
#include "io/export_options.h"
#include "io/frame_exporter.h"
#include "scene/scene_json.h"
#include "sim/checkpoint.h"
#include "sim/export_frame.h"
#include "sim/simulation.h"

namespace py = pybind11;

namespace {

using ff::Error;
using ff::Simulation;

// A NumPy array or scalar as Python lists and numbers (its tolist()), anything else as it is.
py::object plain(const py::handle& v) {
  if (!py::isinstance<py::str>(v) && py::hasattr(v, "tolist")) return v.attr("tolist")();
  return py::reinterpret_borrow<py::object>(v);
}

// The key path ("fluid[0].origin[1]", under `path`) of the first number in
// `v` that is not finite, or "" where every number is.
std::string nonFinite(const py::handle& value, const std::string& path) {
  const py::object v = plain(value);
  if (py::isinstance<py::float_>(v)) return std::isfinite(v.cast<double>()) ? "" : path;
  if (py::isinstance<py::dict>(v)) {
    for (const auto& kv : v.cast<py::dict>()) {
      const std::string key = py::str(kv.first).cast<std::string>();
      const std::string bad = nonFinite(kv.second, path.empty() ? key : path + "." + key);
      if (!bad.empty()) return bad;
    }
  } else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    size_t i = 0;
    for (const auto& e : v) {
      const std::string bad = nonFinite(e, path + "[" + std::to_string(i++) + "]");
      if (!bad.empty()) return bad;
    }
  }
  return "";
}

// Python value -> JSON text (through Python's json module), for the scene
// reader; NumPy arrays and scalars as their lists and numbers. JSON has no
// NaN or infinity: such a number is refused naming `source` and its key path
// under `path` (Python's json would write NaN, which the reader calls invalid JSON).
std::string toJson(const py::handle& value, const std::string& source, const std::string& path) {
  const std::string bad = nonFinite(value, path);
  if (!bad.empty()) throw Error(source + ": " + bad + ": must be a finite number");
  const py::cpp_function tolist([](const py::object& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("Object of type " + py::str(py::type::of(o).attr("__name__")).cast<std::string>() +
                         " is not JSON serializable");
  });
  return py::module_::import("json").attr("dumps")(value, py::arg("default") = tolist).cast<std::string>();
}

std::string cwd() {
  return py::module_::import("os").attr("getcwd")().cast<std::string>();
}

// An (n, 3) float32 array from three columns.
py::array_t<float> columns3(const std::vector<float>& x, const std::vector<float>& y,
                            const std::vector<float>& z) {
  const py::ssize_t n = py::ssize_t(x.size());
  py::array_t<float> a({n, py::ssize_t(3)});
  auto m = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) m(i, 0) = x[size_t(i)], m(i, 1) = y[size_t(i)], m(i, 2) = z[size_t(i)];
  return a;
}

template <class T>
py::array_t<T> column(const std::vector<T>& v) {
  return py::array_t<T>(py::ssize_t(v.size()), v.data());
}

// The Python-side run: a Simulation and what the module adds around it.
class PySimulation {
 public:
  PySimulation(const py::object& scene, const std::string& backend, int device, int threads,
               const py::object& params) {
    ff::checkThreadCount(threads, "threads");
    ff::SceneDesc desc;
    if (py::isinstance<py::dict>(scene))
      desc = ff::parseScene(toJson(scene, "<dict>", ""), "<dict>", cwd());
    else if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__"))
      desc = ff::loadScene(py::str(py::module_::import("os").attr("fspath")(scene)).cast<std::string>());
    else if (scene.is_none())
      desc = ff::defaultScene();
    else
      throw Error("scene: give a file name, a dict in scene syntax, or None for the default scene");
    // Parameters over the scene's own, before the fluid is made and the first
    // target placed (set_params after that leaves what they set: the
    // particle spacing, the first placement, blend_first, adaptive).
    if (!params.is_none()) {
      if (!py::isinstance<py::dict>(params))
        throw Error(
            "params: give a dict in the scene's 'params' syntax, e.g. {'fluid': {'viscosity': 0.03}}");
      readParams(params, desc.params);
      ff::validateParams(desc.params, "<params>");
    }
    std::string note;
    auto b = ff::makeBackend(backend, device, threads, &note, ff::pythonBackendNames());
    sim_ = std::make_unique<Simulation>(std::move(desc), std::move(b));
  }
  explicit PySimulation(std::unique_ptr<Simulation> sim) : sim_(std::move(sim)) {}

  void step() { sim_->step(); }

  // Runs `steps` steps, or for `seconds` more, or until the simulated time
  // reaches `until`; returns the metrics of every step as arrays. Ctrl-C
  // stops it between steps (KeyboardInterrupt).
  py::dict run(long steps, double seconds, double until) {
    const double dt = sim_->scene().params.fluid.time_step;
    const int given = (steps > 0) + (seconds > 0.0) + (until > 0.0);
    if (given != 1) throw Error("run: give exactly one of steps, seconds or until (each > 0)");
    long n = steps;
    if (seconds > 0.0) n = ff::runSteps(seconds, dt, "run: seconds");
    if (until > 0.0) n = stepsUntil(until, dt);
    if (double(n) > ff::kMaxRunSteps)
      throw Error("run: steps: " + std::to_string(n) + " steps are over the limit of 1e+08 steps");
    std::vector<std::vector<double>> cols(ff::kMetricColumns.size());
    // The columns, and their NumPy copies at the end.
    ff::checkMemory(2.0 * double(n) * double(cols.size()) * sizeof(double), "", "run",
                    "the metrics of " + std::to_string(n) + " steps");
    for (auto& c : cols) c.reserve(size_t(n));
    for (long i = 0; i < n; ++i) {
      sim_->step();
      const auto v = ff::metricValues(sim_->metrics());
      for (size_t k = 0; k < v.size(); ++k) cols[k].push_back(v[k]);
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    py::dict out;
    for (size_t k = 0; k < cols.size(); ++k) {
      const ff::MetricColumn& c = ff::kMetricColumns[k];
      out[c.name] = c.count ? py::object(column(std::vector<int64_t>(cols[k].begin(), cols[k].end())))
                            : py::object(column(cols[k]));
    }
    return out;
  }

  // The fewest steps after which the simulated time reaches `until`: 0 where
  // it already has, else one more step where `until` falls between two
  // steps, so that time >= until after the run, less than a step past it.
  // Counted from the current time, not the step count (the step may have
  // changed, set_params), and a time within 1e-6 of `until` (relative) has
  // reached it: the step is a float, and 4 steps of 0.005 s end at
  // 0.0199999996 s. Counted on the frame clock: the fluid's clock leads it
  // by less than a substep where substeps carry over the frame, and that
  // lead may shrink over the steps.
  long stepsUntil(double until, double dt) const {
    ff::checkRunLength(until, dt, "run: until");
    const double tol = 1e-6 * until;
    const double left = until - sim_->frameTime();
    return left <= tol ? 0L : ff::runSteps(left - tol, dt, "run: until");
  }

  py::dict metrics() const {
    py::dict out;
    const auto v = ff::metricValues(sim_->metrics());
    for (size_t k = 0; k < v.size(); ++k) {
      const ff::MetricColumn& c = ff::kMetricColumns[k];
      out[c.name] = c.count ? py::object(py::int_(int64_t(v[k]))) : py::object(py::float_(v[k]));
    }
    return out;
  }

  py::dict fluid() {
    ff::FluidState f;
    sim_->backend().readFluid(f);
    py::dict out;
    out["position"] = columns3(f.x, f.y, f.z);
    out["velocity"] = columns3(f.vx, f.vy, f.vz);
    out["id"] = column(f.id);
    return out;
  }

  py::dict control() {
    ff::ControlSet c;
    ff::ControlFields cf;
    sim_->backend().readControl(c, cf);
    py::dict out;
    out["position"] = columns3(c.x, c.y, c.z);
    out["velocity"] = columns3(c.vx, c.vy, c.vz);
    out["rest_position"] = columns3(c.x0, c.y0, c.z0);
    out["s"] = column(cf.s);
    return out;
  }

  void setTarget(const py::object& target) {
    if (target.is_none()) return sim_->clearTarget();
    sim_->setTarget(ff::parseTargetSpec(ff::parseJsonStrict(toJson(target, "<target>", "target"), "<target>"),
                                        "<target>", "target", cwd()));
  }
  void setRegion(const py::object& region) {
    sim_->setRegion(ff::parseRegionDesc(ff::parseJsonStrict(toJson(region, "<region>", "region"), "<region>"),
                                        "<region>", "region"));
  }
  void setParams(const py::dict& params) {
    ff::Params p = sim_->scene().params;
    readParams(params, p);
    sim_->setParams(p);
  }
  // A dict in the scene's "params" syntax over `p` (only the keys given).
  static void readParams(const py::handle& params, ff::Params& p) {
    ff::parseParamsOverlay(ff::parseJsonStrict(toJson(params, "<params>", "params"), "<params>"), "<params>",
                           "params", p);
  }

  Simulation& sim() { return *sim_; }

 private:
  std::unique_ptr<Simulation> sim_;
};

class PyExporter {
 public:
  PyExporter(const std::string& dir, const std::string& formats, const std::optional<double>& fps,
             long every_steps, bool overwrite) {
    // As the CLI's --fps and --export-every exclude each other (fps was ignored).
    if (fps && every_steps > 0) throw Error("export: give fps or every_steps, not both");
    ff::ExportOptions o;
    o.dir = dir;
    o.formats = ff::parseExportFormats(formats, "formats");
    if (fps) o.fps = *fps;
    o.every_steps = every_steps;
    o.overwrite = overwrite;
    o.overwrite_option = "overwrite=True";
    exporter_ = std::make_unique<ff::FrameExporter>(o);
  }
  // Writes the simulation's current state as the next frame.
  void write(PySimulation& s) {
    ff::readParticleFrame(s.sim(), exporter_->buffer());
    exporter_->write(exporter_->buffer());
  }
  // Writes a frame only if one is due at this time (fps or every_steps).
  bool writeIfDue(PySimulation& s) { return ff::exportFrameIfDue(s.sim(), *exporter_); }
  long frames() const { return exporter_->frames(); }

 private:
  std::unique_ptr<ff::FrameExporter> exporter_;
};

}  // namespace

PYBIND11_MODULE(flowform, m) {
  m.doc() = "flowform: an SPH liquid that flows into a target shape (shape-matching control)";
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  py::class_<PySimulation>(m, "Simulation")
      .def(py::init<const py::object&, const std::string&, int, int, const py::object&>(),
           py::arg("scene") = py::none(), py::arg("backend") = "cpu", py::arg("device") = -1,
           py::arg("threads") = 0, py::arg("params") = py::none(),
           "A run of a scene: a file name, a dict in scene syntax (scenes/README.md), or None for the "
           "built-in default scene. backend: cpu, opencl or auto. params: a dict in the scene's 'params' "
           "syntax over the scene's own, in effect from the start (the fluid's spacing, the first target's "
           "placement), as a scene file's params are; set_params changes them later.")
      .def("step", &PySimulation::step, "One fluid time step.")
      .def(
          "run", &PySimulation::run, py::arg("steps") = 0, py::arg("seconds") = 0.0, py::arg("until") = 0.0,
          "Runs `steps` steps, `seconds` more simulated seconds, or until the simulated time reaches `until` "
          "(no step if it has; else the fewest steps that reach it, so `time` ends at or less than one step "
          "past it); returns each step's metrics as a dict of NumPy arrays (the columns of `flowform run "
          "--metrics`).")
      .def("set_target", &PySimulation::setTarget, py::arg("target"),
           "A target in scene syntax ('sphere', 'bunny.obj', {'shape': 'box', ...}); None switches control "
           "off.")
      .def("set_region", &PySimulation::setRegion, py::arg("region"),
           "The controlled region in scene syntax: 'all', {'box': ...} or {'sphere': ...}.")
      .def("set_params", &PySimulation::setParams, py::arg("params"),
           "Changes parameters now: a dict in the scene's 'params' syntax (only the keys given). A new "
           "cluster stride, half-width or coarse level re-places the control particles at once.")
      .def("fluid", &PySimulation::fluid, "The fluid: position and velocity (n, 3) float32, id (n,) uint32.")
      .def("control", &PySimulation::control,
           "The control particles: position, velocity, rest_position (m, 3) float32, s (m,) float32.")
      .def_property_readonly("metrics", &PySimulation::metrics, "The last step's metrics.")
      .def_property_readonly("time", [](PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("step_count", [](PySimulation& s) { return s.sim().stepCount(); })
      .def_property_readonly("target",
                             [](PySimulation& s) -> py::object {
                               if (!s.sim().target()) return py::none();
                               return py::str(s.sim().target()->label);
                             })
      .def_property_readonly("backend", [](PySimulation& s) { return s.sim().backend().name(); })
      .def(
          "save_checkpoint",
          [](PySimulation& s, const std::string& path) {
            // Refused here in Python's words (the backend's own message names --backend).
            if (!s.sim().backend().writesCheckpoints())
              throw Error(path + ": the " + s.sim().backend().name() +
                          " backend cannot write checkpoints; use backend='cpu'");
            ff::writeCheckpoint(path, s.sim());
          },
          py::arg("path"), "Writes a checkpoint (as `flowform run --checkpoint-every`).");

  m.def(
      "resume",
      [](const std::string& path, const std::string& backend, int device, int threads) {
        ff::checkThreadCount(threads, "threads");
        std::string note;
        auto b = ff::makeBackend(backend, device, threads, &note, ff::pythonBackendNames());
        if (!b->writesCheckpoints())
          throw Error(path + ": the " + b->name() +
                      " backend cannot resume from a checkpoint; use backend='cpu'");
        return PySimulation(ff::loadCheckpoint(path, std::move(b)));
      },
      py::arg("path"), py::arg("backend") = "cpu", py::arg("device") = -1, py::arg("threads") = 0,
      "A Simulation resumed from a checkpoint file.");

  py::class_<PyExporter>(m, "Exporter")
      .def(py::init<const std::string&, const std::string&, const std::optional<double>&, long, bool>(),
           py::arg("dir"), py::arg("formats") = "vtk", py::arg("fps") = py::none(),
           py::arg("every_steps") = 0, py::arg("overwrite") = false,
           "Frames into `dir` (formats: a comma-separated list of vtk, bgeo, ply), as `flowform run "
           "--export`: fps frames per simulated second (default 30) or a frame every every_steps steps, not "
           "both.")
      .def("write", &PyExporter::write, py::arg("sim"), "Writes the current state as the next frame.")
      .def("write_if_due", &PyExporter::writeIfDue, py::arg("sim"),
           "Writes a frame if one is due at the simulation's time; returns whether it did.")
      .def_property_readonly("frames", &PyExporter::frames);
}
