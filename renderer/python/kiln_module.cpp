// The Python module `kiln`: one render job (job/render_job.h) per kiln.render() call, its AOVs as
// NumPy arrays (height × width × channels, float32, exactly the values the EXR stores), its
// metadata and statistics. Options are the option table's, by the same names (look_from for
// --look-from) with the same checks; a refused value or a bad asset raises kiln.InputError with
// the message the CLI prints. The render runs on its own thread without the GIL, and the calling
// thread watches for Ctrl-C: a KeyboardInterrupt cancels the render and is raised when it stops.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <future>
#include <mutex>
#include <string>
#include <thread>

#include "core/error.h"
#include "job/option_table.h"
#include "job/render_job.h"
#include "job/render_sequence.h"

namespace py = pybind11;

namespace kiln {

namespace {

PyObject* error_class = nullptr;        // kiln.Error
PyObject* input_error_class = nullptr;  // kiln.InputError (also a ValueError)
PyObject* time_limit_class = nullptr;   // kiln.TimeLimitError (also a TimeoutError)

// --aovs and friends from "beauty,Z" or ["beauty", "Z"]; --look-from from "1,2,3" or (1, 2, 3).
std::string option_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  // repr of a float is the shortest text that reads back to the same double.
  if (py::isinstance<py::float_>(value)) return py::repr(value).cast<std::string>();
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text;
    for (const py::handle& item : value) text += (text.empty() ? "" : ",") + option_text(item);
    return text;
  }
  throw input_error("", "",
                    "expected a string, number, boolean, list or tuple, got " +
                        py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

// look_from= is --look-from; a value of None leaves the option at its default.
void apply_option(render_options& options, const std::string& keyword, const py::handle& value) {
  if (value.is_none()) return;
  std::string name = keyword;
  for (char& c : name)
    if (c == '_') c = '-';
  const option_spec* spec = find_render_option(name);
  if (!spec) throw input_error("", keyword, "is not a render option (kiln.options() lists them)");
  std::string text;
  try {
    text = option_text(value);
  } catch (const error& e) {
    throw input_error("", "--" + spec->name, e.reason());
  }
  // A flag given False stays off; packets=True means "on".
  if (!spec->choices.empty() && py::isinstance<py::bool_>(value)) text = value.cast<bool>() ? "on" : "off";
  spec->set(options, text);
}

std::string python_call(const std::string& asset, const py::kwargs& kwargs) {
  std::string line = "kiln.render(" + py::repr(py::str(asset)).cast<std::string>();
  for (const auto& [key, value] : kwargs)
    line += ", " + key.cast<std::string>() + "=" + py::repr(value).cast<std::string>();
  return line + ")";
}

py::dict metadata_dict(const exr_metadata& m) {
  py::dict d;
  for (const auto& [key, value] : m.attributes) d[py::str(key)] = value;
  for (const auto& [key, value] : m.float_attributes) d[py::str(key)] = value;
  for (const auto& [key, value] : m.int_attributes) d[py::str(key)] = value;
  // The 16 floats of the file's M44f attributes, in their order (OpenEXR's row vectors: a row of
  // the M44f is a column of kiln's matrices), as a reader of the header gets them.
  py::list camera, ndc;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      camera.append(float(m.world_to_camera[i][j]));
      ndc.append(float(m.world_to_ndc[i][j]));
    }
  d["worldToCamera"] = camera;
  d["worldToNDC"] = ndc;
  return d;
}

py::dict statistics_dict(const render_job_result& r) {
  py::dict d;
  d["width"] = r.width;
  d["height"] = r.height;
  d["camera"] = r.camera_description;
  d["load_seconds"] = r.load_seconds;
  d["build_seconds"] = r.build_seconds;
  d["render_seconds"] = r.stats.seconds;
  d["threads"] = r.stats.threads_used;
  d["camera_rays"] = r.stats.rays.camera;
  d["shadow_rays"] = r.stats.rays.shadow;
  d["reflection_rays"] = r.stats.rays.reflection;
  d["refraction_rays"] = r.stats.rays.refraction;
  d["discarded_samples"] = r.stats.discarded_samples;
  return d;
}

// What kiln.render returns. The film stays here so write() can store it as the CLI would.
struct python_result {
  render_job_result result;
  render_options options;
  py::dict aovs, channels;
  py::dict metadata, stats;
};

// The EXR layers by the names --aovs uses.
std::string aov_name(const std::string& part) {
  if (part == "rgba") return "beauty";
  if (part == "depth") return "Z";
  if (part == "CryptoObject") return "crypto_object";
  if (part == "CryptoMaterial") return "crypto_material";
  return part;
}

// NumPy's C API, loaded by the first render that makes arrays. pybind11 2.10 keeps it in a
// function-local static whose initialiser imports numpy; the import lets other threads run, and one
// that reaches the same static waits there holding the GIL the import needs back: every thread
// hangs, past Ctrl-C. So the first load happens here, behind a mutex waited for without the GIL.
// (The mutex and flag are constant-initialised: no guard of their own.)
void load_numpy_api() {
  static std::atomic<bool> loaded{false};
  static std::mutex loading;
  if (loaded.load(std::memory_order_acquire)) return;
  std::unique_lock<std::mutex> lock(loading, std::defer_lock);
  {
    py::gil_scoped_release unlocked;
    lock.lock();
  }
  if (loaded.load(std::memory_order_relaxed)) return;
  py::detail::npy_api::get();  // throws error_already_set without numpy; the next call tries again
  loaded.store(true, std::memory_order_release);
}

void fill_arrays(python_result& out) {
  load_numpy_api();
  const film& f = out.result.image;
  for (stored_layer& layer : stored_layers(f, out.result.storage)) {
    const py::ssize_t c = py::ssize_t(layer.channels.size());
    py::array_t<float> array({py::ssize_t(f.height), py::ssize_t(f.width), c});
    std::copy(layer.samples.begin(), layer.samples.end(), array.mutable_data());
    const std::string name = aov_name(layer.name);
    out.aovs[py::str(name)] = array;
    out.channels[py::str(name)] = layer.channels;
  }
}

// Runs body (the job's render) on a thread of its own while this one, holding the GIL only
// between waits, checks for Ctrl-C and reports progress.
template <typename Result>
Result run_watched(render_job& job, const py::object& progress, const std::function<Result()>& body) {
  std::atomic<bool> cancel{false};
  render_progress counts;
  job.cancel = &cancel;
  job.progress = &counts;
  std::promise<Result> promise;
  std::future<Result> done = promise.get_future();
  std::thread worker([&body, &promise] {
    try {
      promise.set_value(body());
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  });
  bool interrupted = false;
  for (;;) {
    std::future_status status;
    {
      py::gil_scoped_release unlocked;
      status = done.wait_for(std::chrono::milliseconds(50));
    }
    if (status == std::future_status::ready) break;
    if (!interrupted && PyErr_CheckSignals() != 0) {  // KeyboardInterrupt (or a handler's exception)
      interrupted = true;
      cancel = true;
      continue;  // wait for the render to stop; the exception stays set
    }
    if (!interrupted && !progress.is_none()) {
      try {
        progress(counts.pixels_done.load(), counts.pixels_total.load());
      } catch (py::error_already_set& e) {
        e.restore();
        interrupted = true;
        cancel = true;
      }
    }
  }
  worker.join();
  if (interrupted) {
    try {
      done.get();
    } catch (...) {
    }
    throw py::error_already_set();
  }
  return done.get();
}

render_job_result run_watched(render_job& job, const py::object& progress) {
  return run_watched<render_job_result>(job, progress, [&job] { return run_job(job); });
}

// The arrays, metadata and statistics of a finished render.
python_result finished(render_job_result result, const render_options& options) {
  python_result out;
  out.result = std::move(result);
  out.options = options;
  fill_arrays(out);
  out.metadata = metadata_dict(out.result.metadata);
  out.stats = statistics_dict(out.result);
  return out;
}

// The job of a call: the asset, output= and every keyword as its render option.
render_job python_job(const std::string& asset, const py::object& output, const py::kwargs& kwargs) {
  render_job job;
  job.options.input = asset;
  job.options.quiet = true;
  job.options.command_line = python_call(asset, kwargs);
  if (!output.is_none()) job.options.output = output.cast<std::string>();
  for (const auto& [key, value] : kwargs) apply_option(job.options, key.cast<std::string>(), value);
  return job;
}

// kiln.render_sequence: every frame of frames=, each written (when output= names a pattern) as
// soon as it is rendered, all returned in order.
py::list render_sequence(const std::string& asset, const py::object& output, const py::object& progress,
                         const py::kwargs& kwargs) {
  render_job job = python_job(asset, output, kwargs);
  if (!renders_sequence(job.options))
    throw input_error("", "frames", "render_sequence needs frames= (e.g. frames=\"1-24\") or turntable=N");
  using frames = std::vector<std::pair<render_job_result, render_options>>;
  frames rendered = run_watched<frames>(job, progress, [&job] {
    frames out;
    run_sequence(job,
                 [&out](const render_job_result& result, const render_options& frame, const frame_report&) {
                   if (!frame.output.empty()) write_job_outputs(result, frame);
                   out.emplace_back(result, frame);
                 });
    return out;
  });
  py::list list;
  for (auto& [result, frame] : rendered) list.append(finished(std::move(result), frame));
  return list;
}

python_result render(const std::string& asset, const py::object& output, const py::object& progress,
                     const py::kwargs& kwargs) {
  render_job job = python_job(asset, output, kwargs);
  python_result out;
  out.result = run_watched(job, progress);
  out.options = job.options;
  if (!job.options.output.empty()) {
    py::gil_scoped_release unlocked;
    write_job_outputs(out.result, job.options);
  }
  fill_arrays(out);
  out.metadata = metadata_dict(out.result.metadata);
  out.stats = statistics_dict(out.result);
  return out;
}

void write_result(const python_result& r, const std::string& path, const py::object& preview) {
  render_options options = r.options;
  options.output = path;
  options.preview = preview.is_none() ? std::string() : preview.cast<std::string>();
  check_job(options);
  py::gil_scoped_release unlocked;
  write_job_outputs(r.result, options);
}

py::list option_list() {
  py::list list;
  const render_options defaults;
  for (const option_spec& spec : render_option_table()) {
    py::dict d;
    std::string keyword = spec.name;
    for (char& c : keyword)
      if (c == '-') c = '_';
    d["name"] = keyword;
    d["option"] = "--" + spec.name;
    const char* types[] = {"int", "int", "float", "str", "bool"};
    d["type"] = types[int(spec.type)];
    d["help"] = spec.help;
    d["choices"] = spec.choices;
    const std::optional<std::string> value = spec.get(defaults);
    d["default"] = value ? py::object(py::str(*value)) : py::object(py::none());
    list.append(d);
  }
  return list;
}

// kiln::error as kiln.InputError (bad input: the CLI's exit 2) or kiln.Error, carrying the file,
// the location (a JSON pointer or an option) and the reason; an interrupt as KeyboardInterrupt.
void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const error& e) {
    if (e.kind() == error_kind::interrupted) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
      return;
    }
    PyObject* type = e.kind() == error_kind::input        ? input_error_class
                     : e.kind() == error_kind::time_limit ? time_limit_class
                                                          : error_class;
    py::object instance = py::reinterpret_borrow<py::object>(type)(std::string(e.what()));
    instance.attr("file") = e.file();
    instance.attr("location") = e.location();
    instance.attr("reason") = e.reason();
    PyErr_SetObject(type, instance.ptr());
  }
}

}  // namespace

}  // namespace kiln

PYBIND11_MODULE(kiln, m) {
  using namespace kiln;
  m.doc() = "kiln: renders glTF 2.0 assets with Embree and Whitted shading; AOVs as NumPy arrays";
  m.attr("__version__") = KILN_VERSION;
  error_class = PyErr_NewException("kiln.Error", PyExc_RuntimeError, nullptr);
  py::tuple input_bases = py::make_tuple(py::handle(error_class), py::handle(PyExc_ValueError));
  input_error_class = PyErr_NewException("kiln.InputError", input_bases.ptr(), nullptr);
  py::tuple time_bases = py::make_tuple(py::handle(error_class), py::handle(PyExc_TimeoutError));
  time_limit_class = PyErr_NewException("kiln.TimeLimitError", time_bases.ptr(), nullptr);
  m.attr("Error") = py::handle(error_class);
  m.attr("TimeLimitError") = py::handle(time_limit_class);
  m.attr("InputError") = py::handle(input_error_class);
  py::register_exception_translator(&translate);

  py::class_<python_result>(m, "Result", "One render: its AOVs, metadata and statistics")
      .def_readonly("aovs", &python_result::aovs, "AOV name -> float32 array (height, width, channels)")
      .def_readonly("channels", &python_result::channels, "AOV name -> its EXR channel names")
      .def_readonly("metadata", &python_result::metadata, "The EXR header's attributes")
      .def_readonly("stats", &python_result::stats, "Sizes, timings and ray counts")
      .def("write", &write_result, py::arg("path"), py::arg("preview") = py::none(),
           "Write the EXR (and a PNG/JPEG preview) exactly as kiln render would, atomically")
      .def("__getitem__",
           [](const python_result& r, const std::string& name) { return r.aovs[py::str(name)]; });

  m.def("render", &render, py::arg("asset"), py::kw_only(), py::arg("output") = py::none(),
        py::arg("progress") = py::none(),
        "render(asset, *, output=None, progress=None, **options) -> Result\n\n"
        "Renders asset with the options of `kiln render` (width=, height=, spp=, camera=, aovs=[...],\n"
        "look_from=(x, y, z), ...; kiln.options() lists them). output= also writes the EXR; progress\n"
        "is called as progress(pixels_done, pixels_total). Raises kiln.InputError for bad input.");
  m.def("render_sequence", &render_sequence, py::arg("asset"), py::kw_only(), py::arg("output") = py::none(),
        py::arg("progress") = py::none(),
        "render_sequence(asset, *, frames, output=None, progress=None, **options) -> list[Result]\n\n"
        "Renders the frames of frames=\"FIRST-LAST[:STEP]\" (or turntable=N) as kiln render does: the\n"
        "asset loads once, each frame is posed and the backend updated in place. output= (with ####\n"
        "or %04d) writes each frame as it finishes. Returns one Result per frame, in order.");
  m.def("options", &option_list, "Every render option: name, option, type, help, choices, default");
}
