#include "support/run_kiln.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace kiln::testing {

namespace {

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string scratch_folder(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("kiln_test_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::string copy_scene(const std::string& folder, const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path scenes = fs::path(KILN_SOURCE_DIR) / "scenes";
  fs::create_directories(folder);
  fs::copy_file(scenes / "cornell_box.gltf", fs::path(folder) / name, fs::copy_options::overwrite_existing);
  for (const char* resource : {"cornell_box.bin", "checker.png"})
    fs::copy_file(scenes / resource, fs::path(folder) / resource, fs::copy_options::overwrite_existing);
  return (fs::path(folder) / name).string();
}

namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Whether arguments name option (as "--option" or "--option=value").
bool names(const std::vector<std::string>& arguments, const std::string& option) {
  for (const std::string& a : arguments)
    if (a == option || a.rfind(option + "=", 0) == 0) return true;
  return false;
}

}  // namespace

command_result run_kiln(const std::vector<std::string>& arguments) {
  std::string err_file = scratch_folder("stderr") + "/stderr.txt";
  std::string command = quote(KILN_BINARY);
  for (const std::string& a : arguments) command += " " + quote(a);
  const bool one_sample = !arguments.empty() && arguments[0] == "render" && !names(arguments, "--spp") &&
                          !names(arguments, "--adaptive-threshold") && !names(arguments, "--help");
  if (one_sample) command += " --spp 1";
  const std::string out_file = err_file.substr(0, err_file.size() - 10) + "stdout.txt";
  command += " </dev/null >" + quote(out_file) + " 2>" + quote(err_file);
  int status = std::system(command.c_str());
  command_result result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.stderr_text = file_text(err_file);
  result.stdout_text = file_text(out_file);
  return result;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace kiln::testing
