// What an OpenColorIO config hands OpenColorIO is checked first, as an asset's URIs are: the
// config file (a regular file within kiln's size limit, its entries counted before OpenColorIO's
// quadratic reading), every file a FileTransform on kiln's conversion names (no FIFO, no device,
// within the LUT limit, no further references) and every MatrixTransform's values (finite). Each
// case runs kiln in a child process under a deadline and an address-space limit and measures its
// peak memory, so a regression that blocks on a FIFO, reads /dev/zero forever or reads a config
// for minutes fails the test instead of stalling the suite or the machine.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "support/kiln_process.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using testing::scratch_folder;

const std::string shipped_config = KILN_SOURCE_DIR "/share/ocio/kiln.ocio";

using testing::measured_run;

// Runs kiln with args, killing it after `seconds`; its address space is limited to 2 GiB (except
// under AddressSanitizer), so a read that never ends fails in memory rather than take the machine's.
measured_run run_at_most(const std::vector<std::string>& args, const std::string& dir,
                         double seconds = 15.0) {
  return testing::run_measured(args, dir, seconds, uint64_t(2) << 30);
}

// Expects kiln refused args in time (exit 2, one line naming `names`, nothing written) and in
// bounded memory.
void expect_refused(const std::vector<std::string>& args, const std::string& dir, const std::string& names,
                    const std::string& output) {
  const measured_run run = run_at_most(args, dir);
  std::printf("exit %d in %.2f s, peak %ld KiB: %s", run.exit_code, run.seconds, run.peak_kib,
              run.stderr_text.c_str());
  EXPECT_EQ(run.exit_code, 2) << run.stderr_text;
  EXPECT_EQ(testing::lines(run.stderr_text).size(), 1u) << run.stderr_text;
  EXPECT_NE(run.stderr_text.find(names), std::string::npos) << run.stderr_text;
  EXPECT_LT(run.seconds, 10.0);
  EXPECT_LT(run.peak_kib, 512L << 10);
  EXPECT_FALSE(fs::exists(output)) << output;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// ACEScg's matrix to the reference (ACES2065-1) in kiln's config: the line the variants replace.
const std::string acescg_to_reference =
    "    to_scene_reference: !<MatrixTransform> {matrix: [0.69545224135745176, 0.14067869647029421, "
    "0.16386906217225414, 0, 0.044794563372037771, 0.85967111845642197, 0.095534318171540414, 0, "
    "-0.0055258825581135434, 0.0040252103059786612, 1.0015006722521351, 0, 0, 0, 0, 1]}";

// kiln's config with `line` replaced by `with` and its search path the config's own folder,
// written as dir/name.
std::string config_variant(const std::string& dir, const std::string& name, const std::string& line,
                           const std::string& with) {
  std::string yaml = read_text(shipped_config);
  const size_t at = yaml.find(line);
  EXPECT_NE(at, std::string::npos) << line;
  if (at != std::string::npos) yaml.replace(at, line.size(), with);
  yaml.replace(yaml.find("search_path: \"\""), 15, "search_path: \".\"");
  const std::string path = dir + "/" + name;
  std::ofstream(path) << yaml;
  return path;
}

// ACEScg converting to the reference through a FileTransform of src.
std::string file_transform_config(const std::string& dir, const std::string& name, const std::string& src) {
  return config_variant(
      dir, name, acescg_to_reference,
      "    to_scene_reference: !<FileTransform> {src: \"" + src + "\", interpolation: linear}");
}

struct render_case {
  std::string dir, scene, out;

  explicit render_case(const std::string& name)
      : dir(scratch_folder(name)), scene(testing::copy_scene(dir)), out(dir + "/out.exr") {}

  std::vector<std::string> args(std::vector<std::string> extra) const {
    std::vector<std::string> a = {"render", scene, "-o", out, "--width", "8", "--height", "8", "-q"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
};

TEST(ocio_inputs_cli, a_file_transform_naming_a_fifo_or_a_device_is_refused_before_it_is_opened) {
  const render_case r("ocio_inputs_fifo");
  const std::string fifo = r.dir + "/lut.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Opening the FIFO to read waits for a writer: OpenColorIO used to block there for good.
  expect_refused(
      r.args({"--ocio-config", file_transform_config(r.dir, "fifo.ocio", fifo), "--working-space", "ACEScg"}),
      r.dir, "colour space 'ACEScg' [to_scene_reference]: its FileTransform '" + fifo + "' is a FIFO", r.out);
  // Found along the search path, as OpenColorIO finds it.
  expect_refused(r.args({"--ocio-config", file_transform_config(r.dir, "relative.ocio", "lut.fifo"),
                         "--working-space", "ACEScg"}),
                 r.dir, "its FileTransform 'lut.fifo' (" + fifo + ") is a FIFO, not a regular file", r.out);
  // /dev/zero never ends: OpenColorIO used to read it until the kernel killed kiln (24 GB); so
  // does a link to it with a LUT's name.
  expect_refused(r.args({"--ocio-config", file_transform_config(r.dir, "zero.ocio", "/dev/zero"),
                         "--working-space", "ACEScg"}),
                 r.dir, "its FileTransform '/dev/zero' is a character device, not a regular file", r.out);
  fs::create_symlink("/dev/zero", r.dir + "/zero.cube");
  expect_refused(r.args({"--ocio-config", file_transform_config(r.dir, "link.ocio", "zero.cube"),
                         "--working-space", "ACEScg"}),
                 r.dir, "is a character device, not a regular file", r.out);
  // The preview's display/view, from $OCIO: its files are checked the same way.
  const std::string display =
      config_variant(r.dir, "display.ocio", "offset: [0.055, 0.055, 0.055, 0], direction: inverse}",
                     "offset: [0.055, 0.055, 0.055, 0], direction: inverse}\n"
                     "        - !<FileTransform> {src: lut.fifo}");
  ::setenv("OCIO", display.c_str(), 1);
  expect_refused(r.args({"--preview", r.dir + "/p.png"}), r.dir,
                 "colour space 'sRGB - Display' [from_scene_reference]: its FileTransform 'lut.fifo'", r.out);
  ::unsetenv("OCIO");
}

TEST(ocio_inputs_cli, lut_files_are_bounded_and_refer_to_no_further_files) {
  const render_case r("ocio_inputs_luts");
  // A sparse file past the limit: refused by its size, never read.
  const std::string big = r.dir + "/big.cube";
  std::ofstream(big).close();
  ASSERT_EQ(::truncate(big.c_str(), off_t(17) << 20), 0);
  expect_refused(
      r.args({"--ocio-config", file_transform_config(r.dir, "big.ocio", "big.cube"), "--working-space",
              "ACEScg"}),
      r.dir, "its FileTransform 'big.cube' (" + big + ") is 17825792 bytes, over kiln's limit of 16777216",
      r.out);
  // A CTF file whose <Reference> names another file, which OpenColorIO would open unchecked.
  std::ofstream(r.dir + "/outer.ctf")
      << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<ProcessList id=\"outer\" version=\"2\">\n"
         "  <Reference inBitDepth=\"32f\" outBitDepth=\"32f\" path=\"lut.fifo\"/>\n"
         "</ProcessList>\n";
  expect_refused(r.args({"--ocio-config", file_transform_config(r.dir, "ref.ocio", "outer.ctf"),
                         "--working-space", "ACEScg"}),
                 r.dir, "its FileTransform 'outer.ctf' (" + r.dir + "/outer.ctf) refers to other files",
                 r.out);
  // A small LUT on the preview's path is read as before.
  std::ofstream(r.dir + "/identity.cube") << "LUT_1D_SIZE 2\n0 0 0\n1 1 1\n";
  const std::string display =
      config_variant(r.dir, "display.ocio", "offset: [0.055, 0.055, 0.055, 0], direction: inverse}",
                     "offset: [0.055, 0.055, 0.055, 0], direction: inverse}\n"
                     "        - !<FileTransform> {src: identity.cube, interpolation: linear}");
  const measured_run fine =
      run_at_most(r.args({"--ocio-config", display, "--preview", r.dir + "/p.png"}), r.dir);
  EXPECT_EQ(fine.exit_code, 0) << fine.stderr_text;
  EXPECT_TRUE(fs::exists(r.dir + "/p.png"));
}

TEST(ocio_inputs_cli, configs_too_large_or_too_long_are_refused_before_opencolorio_reads_them) {
  const render_case r("ocio_inputs_configs");
  // 20,000 colour spaces, each with an alias (2.2 MB): OpenColorIO took 38 s to read them.
  std::string yaml =
      "ocio_profile_version: 2\nroles:\n  default: s0\n  scene_linear: s0\n"
      "displays:\n  sRGB:\n    - !<View> {name: Raw, colorspace: s0}\ncolorspaces:\n";
  for (int i = 0; i < 20000; ++i)
    yaml += "  - !<ColorSpace>\n    name: s" + std::to_string(i) + "\n    aliases: [a" + std::to_string(i) +
            "]\n    to_scene_reference: !<MatrixTransform> {}\n";
  const std::string many = r.dir + "/many.ocio";
  std::ofstream(many) << yaml;
  expect_refused(r.args({"--ocio-config", many}), r.dir,
                 "many.ocio: --ocio-config: lists 40008 entries (20000 colour spaces;", r.out);
  expect_refused(r.args({"--ocio-config", many, "--working-space", "s1"}), r.dir, "over kiln's limit of 5000",
                 r.out);
  // 808 MB of junk after a config's first line (sparse: it takes no disk): refused by its size
  // before a byte is read, where OpenColorIO spent 80 s and 2.4 GB.
  const std::string junk = r.dir + "/junk.ocio";
  std::ofstream(junk) << "ocio_profile_version: 2\n";
  ASSERT_EQ(::truncate(junk.c_str(), off_t(808) << 20), 0);
  expect_refused(r.args({"--ocio-config", junk}), r.dir,
                 "junk.ocio: --ocio-config: is 847249408 bytes, over kiln's limit of 4194304", r.out);
  ::setenv("OCIO", junk.c_str(), 1);
  expect_refused(r.args({"--preview", r.dir + "/p.png"}), r.dir, "junk.ocio: $OCIO: is 847249408 bytes",
                 r.out);
  ::unsetenv("OCIO");
  // Not a file at all: said as it is, not "no such file".
  expect_refused(r.args({"--ocio-config", "/dev/zero"}), r.dir,
                 "/dev/zero: --ocio-config: is a character device, not a regular file", r.out);
  const std::string fifo = r.dir + "/config.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused(r.args({"--ocio-config", fifo}), r.dir,
                 "config.fifo: --ocio-config: is a FIFO, not a regular file", r.out);
  // YAML the count cannot follow: an alias repeats a node (a list of any length) in a few bytes.
  const std::string aliased =
      config_variant(r.dir, "aliased.ocio", "  color_timing: ACEScg\n  compositing_linear: ACEScg",
                     "  color_timing: &cg ACEScg\n  compositing_linear: *cg");
  expect_refused(r.args({"--ocio-config", aliased}), r.dir,
                 "aliased.ocio: --ocio-config: line 18 has a YAML anchor (&)", r.out);
  // The shipped config, and the same in CR LF lines, read as before.
  std::string crlf;
  for (const char c : read_text(shipped_config)) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  std::ofstream(r.dir + "/crlf.ocio") << crlf;
  for (const std::string& config : {shipped_config, r.dir + "/crlf.ocio"}) {
    const measured_run fine =
        run_at_most(r.args({"--ocio-config", config, "--working-space", "ACEScg"}), r.dir);
    EXPECT_EQ(fine.exit_code, 0) << config << ": " << fine.stderr_text;
  }
}

TEST(ocio_inputs_cli, non_finite_numbers_on_the_conversion_are_refused) {
  const render_case r("ocio_inputs_nan");
  // NaN in the matrix, infinity in the offset: every converted colour was NaN, and the render
  // discarded its samples and exited 0.
  std::string nan = acescg_to_reference;
  nan.replace(nan.find("0.69545224135745176"), 19, ".nan");
  expect_refused(
      r.args({"--ocio-config", config_variant(r.dir, "nan.ocio", acescg_to_reference, nan), "--working-space",
              "ACEScg"}),
      r.dir,
      "nan.ocio: colour space 'ACEScg' [to_scene_reference]: its MatrixTransform holds nan (matrix value "
      "1 of 16)",
      r.out);
  std::string inf = acescg_to_reference;
  inf.replace(inf.size() - 1, 1, ", offset: [0, -.inf, 0, 0]}");
  expect_refused(r.args({"--ocio-config", config_variant(r.dir, "inf.ocio", acescg_to_reference, inf),
                         "--working-space", "ACEScg"}),
                 r.dir, "its MatrixTransform holds -inf (offset value 2 of 4)", r.out);
  // Through another transform (an exposure), caught on the matrix kiln samples.
  const std::string exposure =
      config_variant(r.dir, "exposure.ocio", acescg_to_reference,
                     "    to_scene_reference: !<GroupTransform>\n      children:\n        - " +
                         acescg_to_reference.substr(acescg_to_reference.find("!<")) +
                         "\n        - !<ExposureContrastTransform> {exposure: .nan}");
  expect_refused(
      r.args({"--ocio-config", exposure, "--working-space", "ACEScg"}), r.dir,
      "exposure.ocio: --working-space: this config converts linear Rec.709 to 'ACEScg' through non-finite "
      "numbers",
      r.out);
}

}  // namespace
}  // namespace kiln
