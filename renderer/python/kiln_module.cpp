// The Python module `kiln`: one render job (job/render_job.h) per kiln.render() call, or a kiln.Scene
// (job/loaded_scene.h) that kiln.load() reads once and renders many times, from a file or from glTF in
// memory (kiln/__init__.py turns a dict or bytes and their buffers and images into the files by URI
// that _load takes). A render's AOVs are NumPy arrays (height × width × channels, float32, exactly
// the values the EXR stores), with its metadata and statistics. Paths are str or os.PathLike. Options are the
// option table's, by the same names (look_from for
// --look-from) with the same checks; a refused value or a bad asset raises kiln.InputError with
// the message the CLI prints, an unknown keyword TypeError with the CLI's suggestion, and what the
// CLI prints as a warning is a kiln.KilnWarning. The render runs on its own thread without the GIL,
// and the calling thread watches for Ctrl-C: a KeyboardInterrupt cancels the render and is raised
// when it stops.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <future>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <variant>
#include <vector>

#include "core/closest_name.h"
#include "core/error.h"
#include "io/exr/exr_shot_time.h"
#include "job/asset_info.h"
#include "job/loaded_scene.h"
#include "job/option_table.h"
#include "job/render_job.h"
#include "job/render_sequence.h"
#include "job/retired_options.h"

namespace py = pybind11;

namespace kiln {

namespace {

PyObject* error_class = nullptr;        // kiln.Error
PyObject* input_error_class = nullptr;  // kiln.InputError (also a ValueError)
PyObject* time_limit_class = nullptr;   // kiln.TimeLimitError (also a TimeoutError)
PyObject* warning_class = nullptr;      // kiln.KilnWarning (a UserWarning)

// What kiln would print as a warning or note during a call, gathered from whichever thread runs the
// job and given to Python's warnings module on the calling thread, with the GIL, once it returns.
struct warning_log {
  std::mutex lock;
  std::vector<std::string> lines;

  void add(const std::string& line) {
    const std::lock_guard<std::mutex> held(lock);
    // The CLI's "kiln: warning: ..." is the warning's category here.
    lines.push_back(line.rfind("warning: ", 0) == 0 ? line.substr(9) : line);
  }
  std::vector<std::string> take() {
    const std::lock_guard<std::mutex> held(lock);
    return std::move(lines);
  }
};

// Issues each line as a kiln.KilnWarning and returns them as a list (Result.warnings). A filter that
// turns warnings into errors raises here.
py::list issue_warnings(const std::vector<std::string>& lines) {
  py::list list;
  for (const std::string& line : lines) {
    if (PyErr_WarnEx(warning_class, line.c_str(), 1) != 0) throw py::error_already_set();
    list.append(line);
  }
  return list;
}

// A path given as str, bytes or os.PathLike (pathlib.Path), as text; anything else is a TypeError.
std::string path_text(const py::handle& value) {
  return py::module_::import("os").attr("fsdecode")(value).cast<std::string>();
}

// --aovs and friends from "beauty,Z" or ["beauty", "Z"]; --look-from from "1,2,3" or (1, 2, 3).
std::string option_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::hasattr(value, "__fspath__")) return path_text(value);  // environment=pathlib.Path(...)
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

std::string keyword_of(std::string name) {
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

// A misspelled keyword is a TypeError, as Python's own are, with the CLI's suggestion.
[[noreturn]] void unknown_keyword(const std::string& function, const std::string& keyword) {
  // Compared as the command line compares them (--spp against --sp), so the two suggest alike.
  std::vector<std::string> options;
  for (const option_spec& spec : render_option_table()) options.push_back("--" + spec.name);
  std::string dashed = "--" + keyword;
  std::replace(dashed.begin(), dashed.end(), '_', '-');
  std::string message = function + "() got an unexpected keyword argument '" + keyword + "'";
  if (const std::optional<std::string> near = closest_name(dashed, options))
    message += "; did you mean '" + keyword_of(near->substr(2)) + "'?";
  else
    message += " (kiln.options() lists the options)";
  throw py::type_error(message);
}

// look_from= is --look-from; a value of None leaves the option at its default.
void apply_option(render_options& options, const std::string& keyword, const py::handle& value,
                  const std::string& function, warning_log& warnings) {
  std::string name = keyword;
  for (char& c : name)
    if (c == '_') c = '-';
  const option_spec* spec = find_render_option(name);
  if (const retired_option* retired = spec ? nullptr : find_retired_option(name)) {
    if (!value.is_none()) warnings.add(retired_option_warning(*retired, keyword + "="));
    return;
  }
  if (!spec) unknown_keyword(function, keyword);
  if (value.is_none()) return;
  if (name == spec->alias)
    warnings.add("warning: " + keyword + "= is deprecated; use " + keyword_of(spec->name) + "=");
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

std::string python_call(const std::string& asset, const py::dict& kwargs) {
  std::string line = "kiln.render(" + py::repr(py::str(asset)).cast<std::string>();
  for (const auto& [key, value] : kwargs)
    line += ", " + key.cast<std::string>() + "=" + py::repr(value).cast<std::string>();
  return line + ")";
}

py::dict metadata_dict(const exr_metadata& m) {
  py::dict d;
  // Numbers as numbers, v2f and v3f as tuples, as the file holds them.
  for (const auto& [key, value] : m.attributes)
    d[py::str(key)] = std::visit(
        [](const auto& v) -> py::object {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, vec2>)
            return py::make_tuple(v.x, v.y);
          else if constexpr (std::is_same_v<T, vec3>)
            return py::make_tuple(v.x, v.y, v.z);
          else
            return py::cast(v);
        },
        value);
  if (m.shot) {  // OpenEXR's framesPerSecond (a fraction) and timeCode ("hh:mm:ss:ff")
    const frame_rate_fraction rate = frame_rate_of(m.shot->fps);
    d["framesPerSecond"] = py::make_tuple(rate.numerator, rate.denominator);
    if (const std::optional<smpte_time_code> t =
            smpte_time_code_of(m.shot->frames_since_start, m.shot->fps)) {
      char text[16];
      std::snprintf(text, sizeof text, "%02d:%02d:%02d:%02d", t->hours, t->minutes, t->seconds, t->frame);
      d["timeCode"] = std::string(text);
    }
  }
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
  py::list warnings;  // each also issued as a kiln.KilnWarning
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

// Calls progress(done, total) with a total above 0 (none is known while the scene loads), each
// change once.
struct progress_caller {
  const py::object& progress;
  std::pair<uint64_t, uint64_t> last{0, 0};

  void operator()(uint64_t done, uint64_t total) {
    if (progress.is_none() || total == 0 || last == std::make_pair(done, total)) return;
    last = {done, total};
    progress(done, total);
  }
};

// Runs body (the job's render) on a thread of its own while this one, holding the GIL only
// between waits, checks for Ctrl-C and reports progress, ending with a call at 100%.
template <typename Result>
Result run_watched(render_job& job, const py::object& progress, const std::function<Result()>& body,
                   warning_log& warnings) {
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
  progress_caller report{progress};
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
    if (!interrupted) {
      try {
        report(counts.pixels_done.load(), counts.pixels_total.load());
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
  std::optional<Result> result;
  try {
    result = done.get();
  } catch (...) {
    issue_warnings(warnings.take());  // what led up to the failure is not lost
    throw;
  }
  const uint64_t total = counts.pixels_total.load();
  report(total, total);
  return std::move(*result);
}

// The arrays, metadata and statistics of a finished render.
python_result finished(render_job_result result, const render_options& options,
                       const std::vector<std::string>& warnings) {
  python_result out;
  out.warnings = issue_warnings(warnings);
  out.result = std::move(result);
  out.options = options;
  fill_arrays(out);
  out.metadata = metadata_dict(out.result.metadata);
  out.stats = statistics_dict(out.result);
  return out;
}

// The job of a call: the asset, output= and every keyword as its render option; what it would print
// as a warning goes to warnings.
render_job python_job(const std::string& function, const std::string& asset, const py::object& output,
                      const py::dict& kwargs, const std::shared_ptr<warning_log>& warnings) {
  render_job job;
  job.warn = [warnings](const std::string& line) { warnings->add(line); };
  job.options.input = asset;
  job.options.quiet = true;
  job.options.command_line = python_call(asset, kwargs);
  if (!output.is_none()) job.options.output = path_text(output);
  for (const auto& [key, value] : kwargs)
    apply_option(job.options, key.cast<std::string>(), value, function, *warnings);
  for (const std::string& line : job_option_warnings(job.options)) warnings->add(line);
  return job;
}

// The frames of a sequence, each written (when output= names a pattern) as soon as it is rendered,
// all returned in order; run(on_frame) renders them (run_sequence, from a file or a kept scene).
py::list sequence_results(render_job& job, const py::object& progress,
                          const std::shared_ptr<warning_log>& warnings,
                          const std::function<void(const frame_handler&)>& run) {
  if (!renders_sequence(job.options))
    throw input_error("", "frames", "render_sequence needs frames= (e.g. frames=\"1-24\") or turntable=N");
  // Each frame keeps the warnings given while it was made.
  using frames = std::vector<std::tuple<render_job_result, render_options, std::vector<std::string>>>;
  frames rendered = run_watched<frames>(
      job, progress,
      [&run, &warnings] {
        frames out;
        run([&](const render_job_result& result, const render_options& frame, const frame_report&) {
          if (!frame.output.empty()) write_job_outputs(result, frame);
          out.emplace_back(result, frame, warnings->take());
        });
        return out;
      },
      *warnings);
  py::list list;
  for (auto& [result, frame, lines] : rendered) list.append(finished(std::move(result), frame, lines));
  return list;
}

// One render by body (run_job, or a kept scene's), written to output= when given.
python_result render_result(render_job& job, const py::object& progress,
                            const std::shared_ptr<warning_log>& warnings,
                            const std::function<render_job_result()>& body) {
  render_job_result result = run_watched<render_job_result>(job, progress, body, *warnings);
  if (!job.options.output.empty()) {
    py::gil_scoped_release unlocked;
    write_job_outputs(result, job.options);
  }
  return finished(std::move(result), job.options, warnings->take());
}

// kiln.render_sequence: the asset loaded once, its frames rendered as kiln render --frames does.
py::list render_sequence(const py::object& asset, const py::object& output, const py::object& progress,
                         const py::kwargs& kwargs) {
  const auto warnings = std::make_shared<warning_log>();
  render_job job = python_job("render_sequence", path_text(asset), output, kwargs, warnings);
  return sequence_results(job, progress, warnings,
                          [&job](const frame_handler& on_frame) { run_sequence(job, on_frame); });
}

python_result render(const py::object& asset, const py::object& output, const py::object& progress,
                     const py::kwargs& kwargs) {
  const auto warnings = std::make_shared<warning_log>();
  render_job job = python_job("render", path_text(asset), output, kwargs, warnings);
  return render_result(job, progress, warnings, [&job] { return run_job(job); });
}

void write_result(const python_result& r, const py::object& path, const py::object& preview) {
  render_options options = r.options;
  options.output = path_text(path);
  options.preview = preview.is_none() ? std::string() : path_text(preview);
  check_job(options);
  py::gil_scoped_release unlocked;
  write_job_outputs(r.result, options);
}

// The Python type of an option's value, as kiln.options() and the docstrings name it.
const char* python_type(const option_spec& spec) {
  const char* types[] = {"int", "int", "float", "str", "bool"};
  return types[int(spec.type)];
}

py::list option_list() {
  py::list list;
  const render_options defaults;
  for (const option_spec& spec : render_option_table()) {
    py::dict d;
    d["name"] = keyword_of(spec.name);
    d["option"] = "--" + spec.name;
    d["type"] = python_type(spec);
    d["help"] = spec.help;
    d["choices"] = spec.choices;
    const std::optional<std::string> value = spec.get(defaults);
    d["default"] = value ? py::object(py::str(*value)) : py::object(py::none());
    list.append(d);
  }
  return list;
}

// A docstring: head, then every option of the table with its type, default and help, as
// help(kiln.render) shows them.
const char* documented(const std::string& head) {
  static std::list<std::string> texts;  // each docstring lives as long as the module
  std::string& text = texts.emplace_back(head + "\n\nOptions (None or leaving one out keeps its default):\n");
  const render_options defaults;
  for (const option_spec& spec : render_option_table()) {
    std::string type = python_type(spec);
    if (!spec.choices.empty()) {
      type.clear();
      for (const std::string& choice : spec.choices)
        type += (type.empty() ? "" : " | ") + ("'" + choice + "'");
    }
    text += "\n    " + keyword_of(spec.name) + ": " + type;
    const std::optional<std::string> value = spec.get(defaults);
    if (value && !value->empty())
      text += " = " + (spec.type == option_type::flag   ? std::string(*value == "true" ? "True" : "False")
                       : spec.type == option_type::text ? "'" + *value + "'"
                                                        : *value);
    text += "\n        " + spec.help + "\n";
  }
  return text.c_str();
}

// The asset's description (job/asset_info.h) that describe makes, as the dict of `kiln info --json`.
py::object info_dict(render_job& job, const std::shared_ptr<warning_log>& warnings,
                     const std::function<asset_info()>& describe) {
  const py::object no_progress = py::none();
  const std::string text = run_watched<std::string>(
      job, no_progress, [&describe] { return asset_info_json(describe()); }, *warnings);
  issue_warnings(warnings->take());
  return py::module_::import("json").attr("loads")(text);
}

// kiln.info: the asset's description, loaded as kiln info loads it.
py::object info(const py::object& asset, const py::kwargs& kwargs) {
  const auto warnings = std::make_shared<warning_log>();
  render_job job = python_job("info", path_text(asset), py::none(), kwargs, warnings);
  return info_dict(job, warnings, [&job] { return describe_asset(job.options, job.cancel, job.warn); });
}

// kiln.Scene: an asset loaded once; every call renders or describes it with load()'s keywords and
// its own (which win), as kiln.render would with both.
struct python_scene {
  std::shared_ptr<loaded_scene> loaded;
  std::string asset;  // its path, or the name of an asset in memory
  std::shared_ptr<const gltf_memory_asset> in_memory;
  py::dict options;  // load()'s keywords

  // The job of one call: load()'s keywords, then the call's own.
  render_job job(const std::string& function, const py::object& output, const py::kwargs& kwargs,
                 const std::shared_ptr<warning_log>& warnings) const {
    py::dict merged = options.attr("copy")();
    for (const auto& [key, value] : kwargs) merged[key] = value;
    render_job made = python_job(function, asset, output, merged, warnings);
    made.options.in_memory = in_memory;
    return made;
  }
};

// The bytes of a bytes object, for an asset in memory.
std::vector<uint8_t> bytes_of(const py::handle& value) {
  const std::string text = py::reinterpret_borrow<py::bytes>(value);
  return std::vector<uint8_t>(text.begin(), text.end());
}

// kiln._load (kiln.load in kiln/__init__.py): the asset at a path, or document (.gltf JSON or .glb
// bytes) with files (URI -> bytes), read and checked once.
python_scene load(const py::object& asset, const py::object& document, const py::dict& files,
                  const py::kwargs& kwargs) {
  python_scene s;
  s.options = py::dict(kwargs).attr("copy")();
  if (!document.is_none()) {
    auto in_memory = std::make_shared<gltf_memory_asset>();
    in_memory->document = bytes_of(document);
    for (const auto& [uri, bytes] : files) in_memory->files[uri.cast<std::string>()] = bytes_of(bytes);
    s.in_memory = std::move(in_memory);
    s.asset = "<memory>";
  } else {
    s.asset = path_text(asset);
  }
  const auto warnings = std::make_shared<warning_log>();
  render_job job = s.job("load", py::none(), py::kwargs(), warnings);
  const py::object no_progress = py::none();
  s.loaded = run_watched<std::shared_ptr<loaded_scene>>(
      job, no_progress, [&job] { return std::make_shared<loaded_scene>(job); }, *warnings);
  issue_warnings(warnings->take());
  return s;
}

python_result scene_render(const python_scene& s, const py::object& output, const py::object& progress,
                           const py::kwargs& kwargs) {
  const auto warnings = std::make_shared<warning_log>();
  render_job job = s.job("render", output, kwargs, warnings);
  const std::shared_ptr<loaded_scene> loaded = s.loaded;
  return render_result(job, progress, warnings, [&job, loaded] { return loaded->render(job); });
}

py::list scene_render_sequence(const python_scene& s, const py::object& output, const py::object& progress,
                               const py::kwargs& kwargs) {
  const auto warnings = std::make_shared<warning_log>();
  render_job job = s.job("render_sequence", output, kwargs, warnings);
  const std::shared_ptr<loaded_scene> loaded = s.loaded;
  return sequence_results(job, progress, warnings, [&job, loaded](const frame_handler& on_frame) {
    run_sequence(job, *loaded, on_frame);
  });
}

py::object scene_info(const python_scene& s, const py::kwargs& kwargs) {
  const auto warnings = std::make_shared<warning_log>();
  render_job job = s.job("info", py::none(), kwargs, warnings);
  const std::shared_ptr<loaded_scene> loaded = s.loaded;
  return info_dict(job, warnings, [&job, loaded] { return loaded->describe(job); });
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

PYBIND11_MODULE(_kiln, m) {
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
  warning_class = PyErr_NewException("kiln.KilnWarning", PyExc_UserWarning, nullptr);
  m.attr("KilnWarning") = py::handle(warning_class);
  py::register_exception_translator(&translate);

  py::class_<python_result>(m, "Result", "One render: its AOVs, metadata and statistics")
      .def_readonly("aovs", &python_result::aovs, "AOV name -> float32 array (height, width, channels)")
      .def_readonly("channels", &python_result::channels, "AOV name -> its EXR channel names")
      .def_readonly("metadata", &python_result::metadata, "The EXR header's attributes")
      .def_readonly("stats", &python_result::stats, "Sizes, timings and ray counts")
      .def_readonly("warnings", &python_result::warnings,
                    "What kiln render would print as warnings and notes (each also a kiln.KilnWarning)")
      .def("write", &write_result, py::arg("path"), py::arg("preview") = py::none(),
           "Write the EXR (and a PNG/JPEG preview) exactly as kiln render would, atomically")
      .def("__getitem__",
           [](const python_result& r, const std::string& name) { return r.aovs[py::str(name)]; });

  py::options signatures;
  signatures.disable_function_signatures();  // the docstrings give them, with every option
  m.def("render", &render, py::arg("asset"), py::kw_only(), py::arg("output") = py::none(),
        py::arg("progress") = py::none(),
        documented(
            "render(asset, *, output=None, progress=None, **options) -> Result\n\n"
            "Renders asset with the options of `kiln render` (width=, height=, spp=, camera=, aovs=[...],\n"
            "look_from=(x, y, z), ...). output= also writes the EXR; progress is called as\n"
            "progress(pixels_done, pixels_total) with a total above 0, the last time at 100%.\n"
            "Raises kiln.InputError for bad input and TypeError for an unknown keyword; warnings are\n"
            "kiln.KilnWarning and Result.warnings."));
  m.def("render_sequence", &render_sequence, py::arg("asset"), py::kw_only(), py::arg("output") = py::none(),
        py::arg("progress") = py::none(),
        "render_sequence(asset, *, frames, output=None, progress=None, **options) -> list[Result]\n\n"
        "Renders the frames of frames=\"FIRST-LAST[:STEP]\" (or turntable=N) as kiln render does: the\n"
        "asset loads once, each frame is posed and the backend updated in place. output= (with ####\n"
        "or %04d) writes each frame as it finishes. Returns one Result per frame, in order. Options:\n"
        "those of render (help(kiln.render) lists them).");
  m.def("info", &info, py::arg("asset"),
        "info(asset, **options) -> dict\n\n"
        "What `kiln info ASSET --json` prints: cameras, animations, variants, lights, scenes, nodes\n"
        "with their geometry, bounds, extensions with kiln's support for each, and the estimate of\n"
        "the render the options describe. Raises kiln.InputError for bad input. Options: those of\n"
        "render (help(kiln.render) lists them).");
  py::class_<python_scene>(m, "Scene",
                           "An asset loaded once (kiln.load), rendered and described as often as wanted")
      .def(
          "render", &scene_render, py::kw_only(), py::arg("output") = py::none(),
          py::arg("progress") = py::none(),
          documented(
              "render(*, output=None, progress=None, **options) -> Result\n\n"
              "Renders the loaded scene as kiln.render(asset, **load_options, **options) would, without\n"
              "reading the asset again: any camera, look_from/look_at, time or frame, lighting, AOVs, size,\n"
              "sampling and crop. An option that changes what is loaded (scene, variant, animation,\n"
              "working_space, ocio_config, the max_* limits, max_memory, allow_outside_files) loads the "
              "asset\n"
              "anew for this render alone; the Scene keeps its own load. Releases the GIL while it renders;\n"
              "renders of one Scene from several threads run one at a time."))
      .def("render_sequence", &scene_render_sequence, py::kw_only(), py::arg("output") = py::none(),
           py::arg("progress") = py::none(),
           "render_sequence(*, frames, output=None, progress=None, **options) -> list[Result]\n\n"
           "The frames of frames=\"FIRST-LAST[:STEP]\" (or turntable=N), each posed from the loaded scene\n"
           "as kiln.render_sequence poses them. Options: those of render (help(kiln.render) lists them).")
      .def(
          "info", &scene_info,
          "info(**options) -> dict\n\n"
          "kiln.info's document for the loaded scene (cameras, animations, variants, lights, nodes, bounds,\n"
          "extensions, the estimate of the render the options describe), without reading the asset again.")
      .def_property_readonly(
          "file", [](const python_scene& s) { return s.asset; },
          "The asset's path, or '<memory>' for glTF given in memory")
      .def_property_readonly(
          "options", [](const python_scene& s) { return s.options.attr("copy")(); },
          "load()'s options: every render's defaults, which its own options override")
      .def("__repr__", [](const python_scene& s) {
        return "kiln.Scene(" + py::repr(py::str(s.asset)).cast<std::string>() + ")";
      });
  m.def("_load", &load, py::arg("asset"), py::kw_only(), py::arg("document") = py::none(),
        py::arg("files") = py::dict(),
        "_load(asset, *, document=None, files={}, **options) -> Scene: kiln.load's native part");
  m.def("options", &option_list, "Every render option: name, option, type, help, choices, default");
}
