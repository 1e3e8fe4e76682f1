#include "app/batch_manifest.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "io/file/input_file.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const char* const job_fields =
    "asset, camera, resolution, spp, frames, fps, animation, turntable, variants, output, overrides";

// The job fields that are render options of the same name (a sequence's time: --frames, --fps,
// --animation, --turntable), written as a string or a number.
bool is_time_field(const std::string& key) {
  return key == "frames" || key == "fps" || key == "animation" || key == "turntable";
}

// Larger manifests are refused: millions of jobs fit in far less.
constexpr uint64_t max_manifest_bytes = uint64_t(512) << 20;

// Through the input-file reader: a FIFO or a device named as the manifest is refused (exit 2)
// instead of blocking or reading forever.
std::string read_text(const std::string& path) {
  const std::vector<uint8_t> bytes = read_whole_input_file(path, {max_manifest_bytes});
  return std::string(bytes.begin(), bytes.end());
}

std::string resolve_asset(const std::string& asset, const std::string& manifest) {
  fs::path p(asset);
  if (p.is_relative()) p = fs::absolute(manifest).parent_path() / p;
  return p.lexically_normal().string();
}

// "640x480" into --width 640 --height 480; false for anything else.
bool resolution_arguments(const std::string& text, std::vector<std::string>& out) {
  const size_t x = text.find('x');
  if (x == std::string::npos || x == 0 || x + 1 == text.size()) return false;
  const std::string w = text.substr(0, x), h = text.substr(x + 1);
  auto digits = [](const std::string& s) { return std::all_of(s.begin(), s.end(), ::isdigit); };
  if (!digits(w) || !digits(h) || w.size() > 9 || h.size() > 9) return false;
  out.insert(out.end(), {"--width", w, "--height", h});
  return true;
}

bool is_integer_text(const std::string& s) {
  return !s.empty() && s.size() < 10 && std::all_of(s.begin(), s.end(), ::isdigit);
}

// {"max-depth": 4, "show-background": true} into render options; a false flag becomes
// --flag=false, which CLI11 reads as off.
std::vector<std::string> option_arguments(const json& object, const std::string& file,
                                          const std::string& where) {
  if (!object.is_object())
    throw input_error(file, where,
                      std::string("expected an object of render options, got ") + object.type_name());
  std::vector<std::string> out;
  for (auto it = object.begin(); it != object.end(); ++it) {
    const std::string name = it.key().rfind("--", 0) == 0 ? it.key() : "--" + it.key();
    const json& value = it.value();
    if (value.is_boolean()) {
      out.push_back(value.get<bool>() ? name : name + "=false");
    } else if (value.is_string()) {
      out.insert(out.end(), {name, value.get<std::string>()});
    } else if (value.is_number()) {
      out.insert(out.end(), {name, value.dump()});
    } else {
      throw input_error(file, where + "/" + it.key(),
                        std::string("expected a string, number or boolean, got ") + value.type_name());
    }
  }
  return out;
}

batch_job_spec json_job(const json& job, const std::string& file, const std::string& where) {
  if (!job.is_object())
    throw input_error(file, where, std::string("expected a job object, got ") + job.type_name());
  batch_job_spec spec;
  spec.where = file + ": " + where;
  auto string_field = [&](const char* key) -> std::string {
    const json& value = job.at(key);
    if (!value.is_string())
      throw input_error(file, where + "/" + key, std::string("expected a string, got ") + value.type_name());
    return value.get<std::string>();
  };
  for (auto it = job.begin(); it != job.end(); ++it) {
    const std::string& key = it.key();
    if (key != "asset" && key != "camera" && key != "resolution" && key != "spp" && key != "output" &&
        key != "overrides" && key != "variants" && !is_time_field(key))
      throw input_error(file, where + "/" + key,
                        "unknown job field (expected " + std::string(job_fields) + ")");
  }
  if (!job.contains("asset")) throw input_error(file, where, "the job has no \"asset\"");
  spec.asset = string_field("asset");
  if (spec.asset.empty()) throw input_error(file, where + "/asset", "empty asset path");
  spec.asset = resolve_asset(spec.asset, file);
  if (job.contains("camera")) {
    const json& camera = job["camera"];
    if (camera.is_number_unsigned())
      spec.camera = std::to_string(camera.get<uint64_t>());
    else
      spec.camera = string_field("camera");
    spec.arguments.insert(spec.arguments.end(), {"--camera", spec.camera});
  }
  if (job.contains("resolution") && !resolution_arguments(string_field("resolution"), spec.arguments))
    throw input_error(file, where + "/resolution",
                      "expected WIDTHxHEIGHT such as 640x480, got " + job["resolution"].dump());
  if (job.contains("spp")) {
    const json& spp = job["spp"];
    if (!spp.is_number_integer())
      throw input_error(file, where + "/spp", "expected an integer, got " + spp.dump());
    spec.arguments.insert(spec.arguments.end(), {"--spp", spp.dump()});
  }
  for (const char* key : {"frames", "fps", "animation", "turntable"}) {
    if (!job.contains(key)) continue;
    const json& value = job[key];
    if (!value.is_string() && !value.is_number())
      throw input_error(file, where + "/" + key,
                        std::string("expected a string or a number, got ") + value.dump());
    spec.arguments.insert(
        spec.arguments.end(),
        {std::string("--") + key, value.is_string() ? value.get<std::string>() : value.dump()});
  }
  if (job.contains("variants")) {
    const json& variants = job["variants"];
    if (variants == "all") {
      spec.all_variants = true;
    } else if (variants.is_array() && !variants.empty()) {
      for (size_t i = 0; i < variants.size(); ++i) {
        if (!variants[i].is_string() && !variants[i].is_number_unsigned())
          throw input_error(file, where + "/variants/" + std::to_string(i),
                            "expected a variant name or index");
        spec.variants.push_back(variants[i].is_string() ? variants[i].get<std::string>()
                                                        : variants[i].dump());
      }
    } else {
      throw input_error(file, where + "/variants",
                        "expected \"all\" or an array of variant names, got " + variants.dump());
    }
  }
  if (job.contains("output")) spec.output = string_field("output");
  if (job.contains("overrides")) {
    std::vector<std::string> overrides = option_arguments(job["overrides"], file, where + "/overrides");
    spec.arguments.insert(spec.arguments.end(), overrides.begin(), overrides.end());
  }
  return spec;
}

// "line L, column C" of a byte offset, for JSON syntax errors.
std::string line_and_column(const std::string& text, size_t byte) {
  byte = std::min(byte, text.size());
  size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(byte), '\n'));
  size_t start = text.rfind('\n', byte == 0 ? 0 : byte - 1);
  size_t column = start == std::string::npos ? byte : byte - start - 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(std::max<size_t>(column, 1));
}

batch_manifest read_json_manifest(const std::string& path) {
  const std::string text = read_text(path);
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string reason = e.what();
    const size_t colon = reason.rfind(": ");
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
    throw input_error(path, line_and_column(text, e.byte), "invalid JSON: " + reason);
  }
  batch_manifest manifest;
  const json* jobs = &doc;
  std::string jobs_where;
  if (doc.is_object()) {
    for (auto it = doc.begin(); it != doc.end(); ++it)
      if (it.key() != "defaults" && it.key() != "jobs")
        throw input_error(path, "/" + it.key(), "unknown field (expected \"defaults\" and \"jobs\")");
    if (!doc.contains("jobs")) throw input_error(path, "", "the manifest has no \"jobs\" array");
    if (doc.contains("defaults"))
      manifest.default_arguments = option_arguments(doc["defaults"], path, "/defaults");
    jobs = &doc["jobs"];
    jobs_where = "/jobs";
  }
  if (!jobs->is_array())
    throw input_error(path, jobs_where.empty() ? "" : jobs_where,
                      std::string("expected an array of jobs, got ") + jobs->type_name());
  for (size_t i = 0; i < jobs->size(); ++i)
    manifest.jobs.push_back(json_job((*jobs)[i], path, jobs_where + "/" + std::to_string(i)));
  return manifest;
}

// One CSV record (RFC 4180 quoting: "a ""b"", c" is one field); false on an unclosed quote.
bool split_csv_line(const std::string& line, std::vector<std::string>& fields) {
  fields.assign(1, "");
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return !quoted;
}

std::string trimmed(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

batch_manifest read_csv_manifest(const std::string& path) {
  std::istringstream in(read_text(path));
  batch_manifest manifest;
  std::vector<std::string> header;
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (trimmed(line).empty()) continue;
    const std::string where = "line " + std::to_string(number);
    std::vector<std::string> fields;
    if (!split_csv_line(line, fields)) throw input_error(path, where, "unclosed quote");
    for (std::string& f : fields) f = trimmed(f);
    if (header.empty()) {
      header = fields;
      for (const std::string& column : header)
        if (column != "asset" && column != "camera" && column != "resolution" && column != "spp" &&
            column != "output" && column != "overrides" && column != "variants" && !is_time_field(column))
          throw input_error(path, where, "unknown column '" + column + "' (expected " + job_fields + ")");
      if (std::find(header.begin(), header.end(), "asset") == header.end())
        throw input_error(path, where, "the header has no 'asset' column");
      continue;
    }
    if (fields.size() != header.size())
      throw input_error(
          path, where,
          "expected " + std::to_string(header.size()) + " fields, got " + std::to_string(fields.size()));
    batch_job_spec spec;
    spec.where = path + ": " + where;
    std::vector<std::string> overrides;
    for (size_t c = 0; c < header.size(); ++c) {
      const std::string& column = header[c];
      const std::string& value = fields[c];
      if (column == "asset") {
        if (value.empty()) throw input_error(path, where, "empty asset path");
        spec.asset = resolve_asset(value, path);
      } else if (value.empty()) {
        continue;  // an empty cell leaves the default
      } else if (column == "camera") {
        spec.camera = value;
        spec.arguments.insert(spec.arguments.end(), {"--camera", value});
      } else if (column == "resolution") {
        if (!resolution_arguments(value, spec.arguments))
          throw input_error(path, where,
                            "resolution: expected WIDTHxHEIGHT such as 640x480, got '" + value + "'");
      } else if (column == "spp") {
        if (!is_integer_text(value))
          throw input_error(path, where, "spp: expected an integer, got '" + value + "'");
        spec.arguments.insert(spec.arguments.end(), {"--spp", value});
      } else if (column == "variants") {
        if (value == "all")
          spec.all_variants = true;
        else
          spec.variants = split_arguments(value);  // names as a shell splits them
      } else if (is_time_field(column)) {
        spec.arguments.insert(spec.arguments.end(), {"--" + column, value});
      } else if (column == "output") {
        spec.output = value;
      } else {
        overrides = split_arguments(value);
      }
    }
    spec.arguments.insert(spec.arguments.end(), overrides.begin(), overrides.end());
    manifest.jobs.push_back(std::move(spec));
  }
  if (header.empty())
    throw input_error(path, "", "empty manifest (expected a header row: " + std::string(job_fields) + ")");
  return manifest;
}

}  // namespace

std::vector<std::string> split_arguments(const std::string& text) { return CLI::detail::split_up(text); }

batch_manifest read_manifest(const std::string& path) {
  const std::string extension = fs::path(path).extension().string();
  if (extension == ".json") return read_json_manifest(path);
  if (extension == ".csv") return read_csv_manifest(path);
  throw input_error(path, "", "a manifest is .json or .csv, got '" + extension + "'");
}

}  // namespace kiln
