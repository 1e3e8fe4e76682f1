#!/usr/bin/env python3
"""tools/farm/kiln_farm.py without a cluster: plan checking, the task list and sbatch scripts of
--dry-run and a written work folder, the EXR header reader against kiln's own --tile bands,
finalize's report on missing and damaged bands, how units are packed into tasks and tasks split
into arrays, --time and --mem from estimates, and a packed task's script run without Slurm;
options and paths that reach the scripts (refused with one line before anything is written, or
quoted so that sbatch and bash read them as given), and files written past links planted in the
work folder. Usage: kiln_farm_test.py SOURCE_DIR KILN_BINARY"""

import contextlib
import io
import json
import os
import shlex
import subprocess
import sys
import tempfile
import unittest

SOURCE_DIR, KILN = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
sys.path.insert(0, os.path.join(SOURCE_DIR, "tools", "farm"))
import kiln_farm  # noqa: E402

CORNELL = os.path.join(SOURCE_DIR, "scenes", "cornell_box.gltf")


def run_main(args):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = kiln_farm.main(args)
    return rc, out.getvalue(), err.getvalue()


def sbatch_directives(script, legacy=False):
    """The options sbatch reads from a script's #SBATCH lines, split as Slurm's sbatch splits them
    (src/sbatch/opt.c, _get_argument): whitespace separates, '...' and "..." group, a backslash
    takes the next character as it is, an unquoted # starts a comment (Slurm 22.05). legacy: as
    older Slurm, where only "..." groups and a # ends the line even inside quotes."""
    args = []
    for line in script.splitlines()[1:]:
        if not line.startswith("#"):
            break  # sbatch stops at the first command
        if not line.startswith("#SBATCH"):
            continue
        rest, i = line[len("#SBATCH"):], 0
        while True:
            while i < len(rest) and rest[i].isspace():
                i += 1
            arg, quote, escape = "", None, False
            while i < len(rest) and (quote or not rest[i].isspace()):
                c = rest[i]
                i += 1
                if escape:
                    escape = False
                elif c == "\\":
                    escape = True
                    continue
                elif c == "#" and (legacy or not quote):
                    i = len(rest)
                    break
                elif quote:
                    if c == quote:
                        quote = None
                        continue
                elif c == '"' or (c == "'" and not legacy):
                    quote = c
                    continue
                arg += c
            if quote:
                raise ValueError(f"unmatched {quote} in {line!r}")
            if not arg:
                break
            args.append(arg)
    return args


class FarmTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def write_plan(self, plan):
        path = os.path.join(self.dir, "plan.json")
        with open(path, "w") as f:
            json.dump(plan, f) if not isinstance(plan, str) else f.write(plan)
        return path

    def job(self, name="a", **overrides):
        job = {"name": name, "asset": CORNELL, "output": os.path.join(self.dir, "out", name + ".exr"),
               "render_args": ["--width", "40", "--height", "10", "--spp", "1"]}
        job.update(overrides)
        return job

    def assert_plan_error(self, plan, expected):
        path = self.write_plan(plan)
        rc, _, err = run_main(["submit", "--plan", path, "--work-dir", self.dir, "--dry-run"])
        self.assertEqual(rc, 2)
        self.assertEqual(err.count("\n"), 1, err)
        self.assertIn(f"{path}: {expected}", err)

    def test_bad_plans_are_refused_with_the_json_path(self):
        self.assert_plan_error("{", "line 1, column 2")
        self.assert_plan_error({"version": 2, "jobs": []}, "/version: expected 1, got 2")
        self.assert_plan_error({"version": 1, "jobs": []}, "/jobs: expected a non-empty array")
        self.assert_plan_error({"version": 1, "jobs": [self.job(), self.job()]}, "/jobs/1/name: 'a' is not unique")
        self.assert_plan_error({"version": 1, "jobs": [self.job(name="a\tb")]},
                               '/jobs/0/name: "a\\tb" contains a control character')
        self.assert_plan_error({"version": 1, "jobs": [self.job(asset="scenes/x.gltf")]},
                               "/jobs/0/asset: 'scenes/x.gltf' is not an absolute path")
        self.assert_plan_error({"version": 1, "jobs": [self.job(), self.job("b", output=self.job()["output"])]},
                               "/jobs/1/output:")
        self.assert_plan_error({"version": 1, "jobs": [self.job(render_args=["--band", "0/2"])]},
                               "/jobs/0/render_args/0: '--band' is set by the farm")
        self.assert_plan_error({"version": 1, "jobs": [self.job(render_args=["--tile", "0/2"])]},
                               "/jobs/0/render_args/0: '--tile' is set by the farm")
        self.assert_plan_error({"version": 1, "jobs": [self.job(render_args="--spp 4")]},
                               "/jobs/0/render_args: expected an array of strings")

    def test_dry_run_prints_both_scripts_and_writes_nothing(self):
        path = self.write_plan({"version": 1, "jobs": [self.job("a"), self.job("b")]})
        work = os.path.join(self.dir, "work")
        rc, out, _ = run_main(["submit", "--plan", path, "--work-dir", work, "--tiles", "3", "--dry-run",
                               "--partition", "render", "--time", "0:30:00", "--cpus-per-task", "4",
                               "--mem", "3G", "--array-limit", "5", "--max-retries", "2", "--kiln", KILN])
        self.assertEqual(rc, 0)
        self.assertFalse(os.path.exists(work))
        for line in ("#SBATCH --array=0-5%5", "#SBATCH --partition=render", "#SBATCH --time=0:30:00",
                     "#SBATCH --cpus-per-task=4", "#SBATCH --mem=3G", "#SBATCH --requeue", "max_retries=2",
                     f"#SBATCH --output={work}/logs/render.%A_%a.log",
                     f"exec python3 {work}/kiln_farm.py finalize --work-dir {work}",
                     "--dependency=afterany:<render job id 0> "):
            self.assertIn(line, out)

    def test_tasks_render_exactly_the_bands_that_stitch(self):
        # Each line of tasks.txt, run as a shell command, renders its band where farm.json says;
        # finalize then stitches them into the single-process image.
        path = self.write_plan({"version": 1, "jobs": [self.job("a"), self.job("b", render_args=[
            "--width", "40", "--height", "10", "--spp", "2", "--threads", "2", "--float"])]})
        options = kiln_farm.parse_args(["submit", "--plan", path, "--work-dir", self.dir, "--tiles", "3",
                                        "--cpus-per-task", "3", "--kiln", KILN])
        plan = kiln_farm.load_plan(path)
        tasks = kiln_farm.build_tasks(plan, KILN, 3, 3, self.dir)
        kiln_farm.write_work_dir(options, plan, tasks)
        with open(os.path.join(self.dir, "tasks.txt")) as f:
            lines = f.read().splitlines()
        self.assertEqual(len(lines), 6)
        self.assertEqual(shlex.split(lines[4]), [KILN, "render", CORNELL, "-o",
                                                 os.path.join(self.dir, "tiles", "0001-b.1of3.exr"), "--band", "1/3",
                                                 "--width", "40", "--height", "10", "--spp", "2", "--threads", "2",
                                                 "--float"])
        self.assertEqual(shlex.split(lines[0])[-2:], ["--threads", "3"])  # the plan left threads open
        for k, line in enumerate(lines):
            if k == 5:
                continue  # band 2 of b stays missing
            subprocess.run(shlex.split(line) + ["-q"], check=True)
        for i in range(3):
            header = kiln_farm.read_exr_header(os.path.join(self.dir, "tiles", f"0000-a.{i}of3.exr"))
            y0, y1 = kiln_farm.band_rows(i, 3, 10)
            self.assertEqual(header["data_window"], [0, y0, 39, y1 - 1])
            self.assertEqual(header["display_window"], [0, 0, 39, 9])
        # Damage band 0 of b: cut it short.
        damaged = os.path.join(self.dir, "tiles", "0001-b.0of3.exr")
        with open(damaged, "rb") as f:
            data = f.read()
        with open(damaged, "wb") as f:
            f.write(data[:len(data) - 40])
        with open(os.path.join(self.dir, "status", "5.rc"), "w") as f:
            f.write("1\n")
        rc, _, err = run_main(["finalize", "--work-dir", self.dir])
        self.assertEqual(rc, 1)
        with open(os.path.join(self.dir, "verify.json")) as f:
            report = json.load(f)
        self.assertFalse(report["ok"])
        a, b = report["jobs"]
        self.assertTrue(a["ok"], a)
        self.assertEqual((a["width"], a["height"]), (40, 10))
        self.assertEqual(a["channels"], ["A:half", "B:half", "G:half", "N.X:half", "N.Y:half", "N.Z:half",
                                         "R:half", "Z:float"])
        self.assertEqual(len(b["problems"]), 2, b)
        self.assertIn("band 0 of 3", b["problems"][0])
        self.assertIn("truncated", b["problems"][0])
        self.assertTrue(b["problems"][1].startswith("band 2 of 3 missing (task 5: exit 1; log "), b)
        self.assertFalse(os.path.exists(b["output"]))
        # The stitched output has the bytes of a single-process render apart from its header.
        reference = os.path.join(self.dir, "reference.exr")
        subprocess.run([KILN, "render", CORNELL, "-o", reference, "--width", "40", "--height", "10", "--spp", "1",
                        "-q"], check=True)
        self.assertEqual(kiln_farm.read_exr_header(reference), kiln_farm.read_exr_header(a["output"]))
        diff = subprocess.run(["idiff", "-q", "-fail", "0", "-failpercent", "0", "-warn", "0", "-a", reference,
                               a["output"]], capture_output=True)
        self.assertEqual(diff.returncode, 0, diff.stdout)

    def test_any_name_kiln_batch_makes_is_accepted_and_gets_safe_band_files(self):
        # kiln batch names a job by its output under --out-dir: spaces, folders, quotes, any script.
        names = ["my shot", "sub dir/a b", "it's $HOME", "ünïcødé 名前", "-leading", ".hidden", "a_b", "a b"]
        jobs = [self.job(n, output=os.path.join(self.dir, "out", f"{k}.exr")) for k, n in enumerate(names)]
        plan = kiln_farm.load_plan(self.write_plan({"version": 1, "jobs": jobs}))
        tasks = kiln_farm.build_tasks(plan, KILN, 2, 1, self.dir)
        tiles = [argv[argv.index("-o") + 1] for _, _, argv in tasks]
        self.assertEqual(len(set(tiles)), len(tiles))  # "a_b" and "a b" do not collide
        for tile in tiles:
            self.assertEqual(os.path.dirname(tile), os.path.join(self.dir, "tiles"))
            self.assertRegex(os.path.basename(tile), r"^[0-9]{4}-[A-Za-z0-9_.+-]+\.[01]of2\.exr$")
        self.assertEqual(os.path.basename(tiles[2]), "0001-sub_dir_a_b.0of2.exr")

    def test_one_band_is_moved_into_place(self):
        path = self.write_plan({"version": 1, "jobs": [self.job("whole")]})
        options = kiln_farm.parse_args(["submit", "--plan", path, "--work-dir", self.dir, "--kiln", KILN])
        plan = kiln_farm.load_plan(path)
        tasks = kiln_farm.build_tasks(plan, KILN, 1, 1, self.dir)
        kiln_farm.write_work_dir(options, plan, tasks)
        with open(os.path.join(self.dir, "tasks.txt")) as f:
            argv = shlex.split(f.read())
        self.assertNotIn("--band", argv)
        subprocess.run(argv + ["-q"], check=True)
        rc, _, _ = run_main(["finalize", "--work-dir", self.dir])
        self.assertEqual(rc, 0)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "tiles", "whole.0of1.exr")))
        header = kiln_farm.read_exr_header(self.job("whole")["output"])
        self.assertEqual(header["data_window"], [0, 0, 39, 9])

    def fake_kiln(self, with_plan_only):
        """A kiln stand-in whose batch command writes a one-job plan and records its arguments."""
        path = os.path.join(self.dir, "fake_kiln")
        job = json.dumps({"version": 1, "jobs": [self.job("from_manifest")]})
        help_text = "--plan-only PLAN  write the resolved plan" if with_plan_only else "Subcommands: render"
        with open(path, "w") as f:
            f.write("#!/bin/sh\n"
                    f"[ \"$2\" = --help ] && {{ echo '{help_text}'; exit 0; }}\n"
                    f"echo \"$@\" >{self.dir}/batch_args\n"
                    "while [ \"$1\" != --plan-only ]; do shift; done\n"
                    f"echo '{job}' >\"$2\"\n")
        os.chmod(path, 0o755)
        return path

    def test_manifest_goes_through_kiln_batch_plan_only(self):
        kiln = self.fake_kiln(with_plan_only=True)
        work = os.path.join(self.dir, "work")
        rc, out, err = run_main(["submit", "--manifest", "shots.csv", "--out-dir", "renders", "--work-dir", work,
                                 "--kiln", kiln, "--tiles", "2", "--dry-run", "--", "--spp", "4"])
        self.assertEqual(rc, 0, err)
        with open(os.path.join(self.dir, "batch_args")) as f:
            self.assertEqual(f.read().split(), ["batch", "--manifest", os.path.abspath("shots.csv"), "--out-dir",
                                                os.path.abspath("renders"), "--plan-only",
                                                os.path.join(work, "plan.json"), "--spp", "4"])
        self.assertIn("#SBATCH --array=0-1\n", out)  # the plan's one job in two bands

    def test_manifest_needs_a_kiln_with_plan_only(self):
        kiln = self.fake_kiln(with_plan_only=False)
        rc, _, err = run_main(["submit", "--manifest", "shots.csv", "--out-dir", "renders", "--work-dir", self.dir,
                               "--kiln", kiln, "--dry-run"])
        self.assertEqual(rc, 2)
        self.assertIn("'kiln batch --plan-only' is not supported by this binary", err)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "batch_args")))

    def test_packing_and_splitting_arithmetic(self):
        # Without estimates: as many units a task as keep 10,000 within --target-tasks.
        packs = kiln_farm.pack_units(10000, None, None, 300.0, 500)
        self.assertEqual((len(packs), max(map(len, packs))), (500, 20))
        self.assertEqual([u for p in packs for u in p], list(range(10000)))  # each unit once, in order
        self.assertEqual(len(kiln_farm.pack_units(40, None, None, 300.0, 500)), 40)  # small: one a task
        self.assertEqual([len(p) for p in kiln_farm.pack_units(41, None, 3, 300.0, 500)], [3] * 13 + [2])
        # With estimates: units fill tasks up to --task-seconds; a longer one goes alone.
        estimates = [(100.0, 1), (150.0, 1), (100.0, 1), (400.0, 1), (10.0, 1), (10.0, 1)]
        self.assertEqual(kiln_farm.pack_units(6, estimates, None, 300.0, 500), [[0, 1], [2], [3], [4, 5]])
        self.assertEqual(kiln_farm.pack_units(6, estimates, 4, 300.0, 500), [[0, 1, 2, 3], [4, 5]])
        # Arrays: indices 0..n-1 stay below MaxArraySize.
        self.assertEqual(kiln_farm.split_arrays(14, 5), [(0, 5), (5, 5), (10, 4)])
        self.assertEqual(kiln_farm.split_arrays(5, 5), [(0, 5)])
        self.assertEqual(kiln_farm.split_arrays(500, 1001), [(0, 500)])
        self.assertEqual(len(kiln_farm.split_arrays(10000, 1001)), 10)

    def test_max_array_size_comes_from_scontrol(self):
        fake = os.path.join(self.dir, "bin")
        os.makedirs(fake)
        with open(os.path.join(fake, "scontrol"), "w") as f:
            f.write("#!/bin/sh\necho 'MaxArraySize            = 7'\necho 'MaxJobCount = 10000'\n")
        os.chmod(os.path.join(fake, "scontrol"), 0o755)
        path = os.environ["PATH"]
        try:
            os.environ["PATH"] = fake + os.pathsep + path
            self.assertEqual(kiln_farm.cluster_max_array_size(), 7)
            os.environ["PATH"] = os.path.join(self.dir, "none")  # no scontrol: Slurm's default
            self.assertEqual(kiln_farm.cluster_max_array_size(), 1001)
        finally:
            os.environ["PATH"] = path

    def test_dry_run_splits_into_arrays_and_the_finalize_job_waits_for_all(self):
        path = self.write_plan({"version": 1, "jobs": [self.job(f"j{i}") for i in range(40)]})
        rc, out, _ = run_main(["submit", "--plan", path, "--work-dir", self.dir, "--dry-run", "--max-array-size", "5",
                               "--jobs-per-task", "3", "--array-limit", "2", "--kiln", KILN])
        self.assertEqual(rc, 0)
        self.assertIn("40 units (40 jobs x 1 bands) in 14 tasks (at most 3 units a task) in 3 arrays "
                      "(MaxArraySize 5); --time 01:00:00 --mem 2G", out)
        for first, last in ((0, 4), (5, 4), (10, 3)):
            self.assertIn(f"# sbatch --parsable --array=0-{last}%2 --export=ALL,KILN_FARM_FIRST_TASK={first} "
                          f"{self.dir}/render.sbatch\n", out)
        self.assertIn("--dependency=afterany:<render job id 0>:<render job id 1>:<render job id 2> ", out)

    def test_a_studio_batch_is_a_few_hundred_tasks(self):
        jobs = [self.job(f"asset{i:05d}") for i in range(10000)]
        path = self.write_plan({"version": 1, "jobs": jobs})
        rc, out, _ = run_main(["submit", "--plan", path, "--work-dir", self.dir, "--dry-run", "--kiln", KILN,
                               "--max-array-size", "1001"])
        self.assertEqual(rc, 0)
        self.assertIn("10000 units (10000 jobs x 1 bands) in 500 tasks (at most 20 units a task) in 1 arrays", out)
        rc, out, _ = run_main(["submit", "--plan", path, "--work-dir", self.dir, "--dry-run", "--kiln", KILN,
                               "--max-array-size", "101", "--tiles", "2", "--target-tasks", "300"])
        self.assertIn("20000 units (10000 jobs x 2 bands) in 299 tasks (at most 67 units a task) in 3 arrays", out)

    def test_estimates_size_time_mem_and_packing(self):
        jobs = [self.job(f"j{i}", estimate={"seconds": 100.0, "peak_memory_bytes": 1 << 30}) for i in range(7)]
        path = self.write_plan({"version": 1, "jobs": jobs})
        rc, out, _ = run_main(["submit", "--plan", path, "--work-dir", self.dir, "--dry-run", "--kiln", KILN,
                               "--max-array-size", "1001", "--max-retries", "0"])
        self.assertEqual(rc, 0)
        # 3 jobs of 100 s a task (300 s): 3 x 30 s start + 3 x 300 s = 990 s, 17 minutes;
        # 256 MB + 1.5 x 1 GB = 1792 MB.
        self.assertIn("in 3 tasks (at most 3 units a task) in 1 arrays (MaxArraySize 1001); "
                      "--time 00:17:00 --mem 1792M", out)
        rc, out, _ = run_main(["submit", "--plan", path, "--work-dir", self.dir, "--dry-run", "--kiln", KILN,
                               "--max-array-size", "1001", "--time", "2:00:00", "--mem", "8G", "--tiles", "2"])
        self.assertIn("14 units (7 jobs x 2 bands) in 3 tasks (at most 6 units a task)", out)
        self.assertIn("--time 2:00:00 --mem 8G", out)
        self.assert_plan_error({"version": 1, "jobs": [self.job(estimate={"seconds": 1, "peak_memory_bytes": 0,
                                                                          "render_seconds": "x"})]},
                               "/jobs/0/estimate/render_seconds: expected a non-negative number")
        self.assert_plan_error({"version": 1, "jobs": [self.job(estimate={"seconds": -1, "peak_memory_bytes": 0})]},
                               "/jobs/0/estimate/seconds: expected a non-negative number")

    def test_unit_estimates_from_kiln_plans(self):
        # kiln's estimate: load once a band, the one-thread render split over threads and bands;
        # a job without one (its asset did not load) counts as the largest of the others.
        kiln_style = {"seconds": 41.0, "load_seconds": 1.0, "render_seconds": 40.0, "peak_memory_bytes": 100}
        plan = {"jobs": [self.job("a", estimate=kiln_style), self.job("b", render_args=["--threads", "8"],
                                                                      estimate=kiln_style), self.job("c")]}
        self.assertEqual(kiln_farm.unit_estimates(plan, 2, 4),
                         [(6.0, 100), (6.0, 100), (3.5, 100), (3.5, 100), (6.0, 100), (6.0, 100)])
        self.assertIsNone(kiln_farm.unit_estimates({"jobs": [self.job("c")]}, 1, 1))

    def test_a_packed_task_renders_resumes_and_reports_each_job(self):
        # Run the render script as Slurm would run task 1 of an array starting at task 0: its three
        # units one after another; the missing asset's fails alone and the task exits with its 2.
        jobs = [self.job(f"j{i}") for i in range(5)]
        jobs[3]["asset"] = os.path.join(self.dir, "missing.gltf")
        path = self.write_plan({"version": 1, "jobs": jobs})
        options = kiln_farm.parse_args(["submit", "--plan", path, "--work-dir", self.dir, "--kiln", KILN,
                                        "--jobs-per-task", "3", "--max-retries", "0"])
        kiln_farm.size_resources(options, None, None)
        plan = kiln_farm.load_plan(path)
        tasks = kiln_farm.build_tasks(plan, KILN, 1, 1, self.dir)
        packs = kiln_farm.pack_units(len(tasks), None, 3, 300.0, 500)
        self.assertEqual(packs, [[0, 1, 2], [3, 4]])
        kiln_farm.write_work_dir(options, plan, tasks, packs, [(0, 1), (1, 1)])
        script = os.path.join(self.dir, "render.sbatch")
        with open(script, "w") as f:
            f.write(kiln_farm.render_script(options, 1))
        env = dict(os.environ, SLURM_ARRAY_TASK_ID="0", KILN_FARM_FIRST_TASK="1")
        run = subprocess.run(["bash", script], env=env, capture_output=True, text=True)
        self.assertEqual(run.returncode, 2, run.stderr)
        self.assertIn("kiln farm: task 1 attempt 0 (unit 4)", run.stdout)
        with open(os.path.join(self.dir, "status", "3.rc")) as f:
            self.assertEqual(f.read().strip(), "2")
        # A requeued task skips the unit that finished: unit 4 is not rendered again.
        run = subprocess.run(["bash", script], env=env, capture_output=True, text=True)
        self.assertEqual(run.returncode, 2)
        self.assertNotIn("(unit 4)", run.stdout)
        rc, _, _ = run_main(["finalize", "--work-dir", self.dir])
        self.assertEqual(rc, 1)
        with open(os.path.join(self.dir, "verify.json")) as f:
            report = {j["name"]: j for j in json.load(f)["jobs"]}
        self.assertTrue(report["j4"]["ok"], report["j4"])
        self.assertEqual(report["j3"]["problems"],
                         [f"band 0 of 1 missing (task 1: exit 2; log {self.dir}/logs/render.*_0.log)"])
        for name in ("j0", "j1", "j2"):  # task 0 never ran
            self.assertIn("never ran to the end", report[name]["problems"][0])

    def test_a_turntable_splits_into_a_job_per_frame_whose_bands_stitch_into_the_sequences_frames(self):
        # kiln batch --plan-only turns a manifest job's "turntable" into one job per frame, each with
        # --turntable N --frame F; the farm renders each in bands, and the stitched frames are
        # those of `kiln render --turntable N`.
        manifest = os.path.join(self.dir, "shots.json")
        with open(manifest, "w") as f:
            json.dump({"defaults": {"width": 16, "height": 8, "spp": 1},
                       "jobs": [{"asset": CORNELL, "turntable": 3}]}, f)
        work = os.path.join(self.dir, "work")
        out_dir = os.path.join(self.dir, "renders")
        os.makedirs(work)
        plan_path = os.path.join(work, "plan.json")
        kiln_farm.plan_from_manifest(KILN, manifest, out_dir, ["--no-estimates"], plan_path)
        plan = kiln_farm.load_plan(plan_path)
        self.assertEqual([j["name"] for j in plan["jobs"]], ["cornell_box.0001", "cornell_box.0002",
                                                            "cornell_box.0003"])
        for frame, job in enumerate(plan["jobs"], 1):
            args = job["render_args"]
            self.assertEqual(kiln_farm.option_value(args, "--turntable"), "3")
            self.assertEqual(kiln_farm.option_value(args, "--frame"), str(frame))
        options = kiln_farm.parse_args(["submit", "--plan", plan_path, "--work-dir", work, "--tiles", "2",
                                        "--kiln", KILN])
        tasks = kiln_farm.build_tasks(plan, KILN, 2, 1, work)
        self.assertEqual(len(tasks), 6)
        kiln_farm.write_work_dir(options, plan, tasks)
        with open(os.path.join(work, "tasks.txt")) as f:
            for line in f.read().splitlines():
                subprocess.run(shlex.split(line) + ["-q"], check=True)
        rc, _, err = run_main(["finalize", "--work-dir", work])
        self.assertEqual(rc, 0, err)
        sequence = os.path.join(self.dir, "seq.####.exr")
        subprocess.run([KILN, "render", CORNELL, "-o", sequence, "--turntable", "3", "--width", "16", "--height", "8",
                        "--spp", "1", "--threads", "1", "-q"], check=True)
        for frame in (1, 2, 3):
            stitched = os.path.join(out_dir, f"cornell_box.{frame:04d}.exr")
            alone = os.path.join(self.dir, f"seq.{frame:04d}.exr")
            diff = subprocess.run(["idiff", "-q", "-fail", "0", "-failpercent", "0", "-warn", "0", "-a", alone,
                                   stitched], capture_output=True)
            self.assertEqual(diff.returncode, 0, diff.stdout)

    # Options and paths that reach the generated scripts (issue 43, item 7).

    def fake_slurm(self):
        """A PATH folder whose sbatch records each call's arguments (one JSON list a line) and
        answers a job id, and whose scancel does nothing: submit runs without a cluster."""
        folder = os.path.join(self.dir, "fake_bin")
        os.makedirs(folder, exist_ok=True)
        calls = os.path.join(self.dir, "sbatch_calls")
        with open(os.path.join(folder, "sbatch"), "w") as f:
            f.write("#!/usr/bin/env python3\nimport json, sys\n"
                    f"with open({calls!r}, 'a') as f:\n    f.write(json.dumps(sys.argv[1:]) + '\\n')\n"
                    f"print(sum(1 for _ in open({calls!r})))\n")
        with open(os.path.join(folder, "scancel"), "w") as f:
            f.write("#!/bin/sh\nexit 0\n")
        for name in ("sbatch", "scancel"):
            os.chmod(os.path.join(folder, name), 0o755)
        return folder, calls

    def submit_with_fake_slurm(self, args):
        folder, calls = self.fake_slurm()
        path = os.environ["PATH"]
        os.environ["PATH"] = folder + os.pathsep + path
        try:
            rc, out, err = run_main(["submit", "--max-array-size", "1001"] + args)
        finally:
            os.environ["PATH"] = path
        submitted = []
        if os.path.exists(calls):
            with open(calls) as f:
                submitted = [json.loads(line) for line in f]
        return rc, out, err, submitted

    def assert_option_refused(self, args, option, problem, work):
        rc, out, err, submitted = self.submit_with_fake_slurm(args)
        self.assertEqual(rc, 2, out + err)
        self.assertEqual(err.count("\n"), 1, err)
        self.assertTrue(err.startswith(f"kiln farm: {option} "), err)
        self.assertIn(problem, err)
        self.assertEqual(submitted, [])
        self.assertFalse(os.path.lexists(work), f"{work} was written")

    def test_a_newline_in_an_option_is_refused_before_anything_is_written(self):
        # Each of these became a line of render.sbatch/finalize.sbatch (or of tasks.txt): a
        # newline in one ran the rest as a command on the node.
        plan = self.write_plan({"version": 1, "jobs": [self.job()]})
        marker = os.path.join(self.dir, "pwned")
        inject = f"\ntouch {marker}\n"
        work = os.path.join(self.dir, "work")
        base = ["--plan", plan, "--kiln", KILN, "--time", "5:00", "--mem", "1G"]
        for option in ("--job-name", "--time", "--mem", "--partition", "--kiln"):
            value = {"--job-name": "kiln", "--time": "5:00", "--mem": "1G", "--partition": "render",
                     "--kiln": KILN}[option] + inject
            with self.subTest(option=option):
                self.assert_option_refused(base + ["--work-dir", work, option, value], option,
                                           "contains a newline", work)
        with self.subTest(option="--work-dir"):
            bad_work = os.path.join(self.dir, "work" + inject.rstrip("\n"))
            self.assert_option_refused(base + ["--work-dir", bad_work], "--work-dir", "contains a newline", bad_work)
            self.assertEqual(sorted(os.listdir(self.dir)), ["fake_bin", "plan.json"])
        with self.subTest(option="--out-dir"):
            kiln = self.fake_kiln(with_plan_only=True)
            self.assert_option_refused(["--manifest", "shots.csv", "--out-dir", "renders" + inject, "--kiln", kiln,
                                        "--work-dir", work], "--out-dir", "contains a newline", work)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "batch_args")))  # kiln batch never ran
        with self.subTest(option="kiln batch defaults"):
            self.assert_option_refused(["--manifest", "shots.csv", "--out-dir", "renders", "--kiln", kiln,
                                        "--work-dir", work, "--", "--environment", "sky.hdr" + inject],
                                       "kiln batch default", "contains a newline", work)
        self.assertFalse(os.path.exists(marker))

    def test_slurm_values_are_checked_against_what_slurm_accepts(self):
        plan = self.write_plan({"version": 1, "jobs": [self.job()]})
        work = os.path.join(self.dir, "work")
        base = ["--plan", plan, "--kiln", KILN, "--work-dir", work]
        refused = [("--time", "1h", "not a Slurm time"), ("--time", "1:2:3:4", "not a Slurm time"),
                   ("--time", "5 ", "not a Slurm time"), ("--time", "1-2-3", "not a Slurm time"),
                   ("--mem", "1.5G", "not a Slurm memory size"), ("--mem", "4GB", "not a Slurm memory size"),
                   ("--mem", "", "not a Slurm memory size"),
                   ("--partition", "a b", "not a Slurm partition name"),
                   ("--partition", "render;touch x", "not a Slurm partition name"),
                   ("--partition", "a,", "not a Slurm partition name"),
                   ("--job-name", "", "is empty"), ("--job-name", "a\tb", "contains a control character"),
                   ("--job-name", "a\rb", "contains a control character"),
                   ("--work-dir", os.path.join(self.dir, "a\\b"), "contains a backslash")]
        for option, value, problem in refused:
            with self.subTest(option=option, value=value):
                args = base + [option, value] if option != "--work-dir" else base[:-1] + [value]
                self.assert_option_refused(args, option, problem, work if option != "--work-dir" else value)
        accepted = [("--time", t) for t in ("5", "5:30", "1:00:00", "2-0", "2-12:30", "2-12:30:15", "UNLIMITED",
                                            "infinite")]
        accepted += [("--mem", m) for m in ("4096", "500M", "4G", "1T", "64k", "2g")]
        accepted += [("--partition", p) for p in ("render", "gpu_a100.long-2", "short,long")]
        for option, value in accepted:
            with self.subTest(option=option, value=value):
                rc, out, err = run_main(["submit", "--dry-run", "--max-array-size", "1001"] + base + [option, value])
                self.assertEqual(rc, 0, err)
                self.assertIn(f"#SBATCH {option}={value}\n", out)

    def test_scripts_with_hostile_paths_and_names_parse_and_run_no_injected_command(self):
        # Quotes, $(...), backticks, #, % and spaces in the job name, the work folder, the kiln
        # binary's path, the asset's and the output's: the scripts are valid bash, sbatch reads
        # the job name and log path exactly, and running them renders and verifies the job
        # without running any of the embedded commands.
        # Each embedded command would create pwnedN in the folder the scripts run in (self.dir).
        hostile = lambda i: f"a b 'q\" $(touch pwned{i}) `touch pwned{i}` #x %j ;"
        folder = os.path.join(self.dir, hostile(0))
        os.makedirs(os.path.join(folder, "assets"))
        for name in ("cornell_box.gltf", "cornell_box.bin", "checker.png"):
            with open(os.path.join(SOURCE_DIR, "scenes", name), "rb") as src, \
                    open(os.path.join(folder, "assets", name), "wb") as dst:
                dst.write(src.read())
        asset = os.path.join(folder, "assets", "cornell_box.gltf")
        kiln = os.path.join(folder, hostile(1) + " kiln")
        os.symlink(KILN, kiln)
        job = self.job(hostile(2), asset=asset, output=os.path.join(folder, "out " + hostile(3), "o.exr"))
        plan = self.write_plan({"version": 1, "jobs": [job]})
        work = os.path.join(folder, "work " + hostile(4))
        job_name = "shot " + hostile(5)
        rc, out, err, submitted = self.submit_with_fake_slurm(
            ["--plan", plan, "--kiln", kiln, "--work-dir", work, "--job-name", job_name, "--tiles", "2",
             "--time", "1-0:05", "--mem", "2G", "--partition", "render,short", "--max-retries", "0"])
        self.assertEqual(rc, 0, err)
        render, finalize = (os.path.join(work, n) for n in ("render.sbatch", "finalize.sbatch"))
        self.assertEqual(submitted, [["--parsable", "--array=0-1", "--export=ALL,KILN_FARM_FIRST_TASK=0", render],
                                     ["--parsable", "--dependency=afterany:1", "--kill-on-invalid-dep=no", finalize]])
        logs = os.path.join(work.replace("%", "%%"), "logs")
        for script, name, log, extra in ((render, "render", "render.%A_%a.log",
                                          ["--array=0-1", "--cpus-per-task=1", "--ntasks=1", "--nodes=1", "--requeue",
                                           "--open-mode=append"]),
                                         (finalize, "stitch", "finalize.%j.log",
                                          ["--cpus-per-task=1", "--ntasks=1", "--nodes=1"])):
            with open(script) as f:
                text = f.read()
            check = subprocess.run(["bash", "-n", script], capture_output=True, text=True)
            self.assertEqual(check.returncode, 0, check.stderr)
            expected = [f"--job-name={job_name}-{name}", "--partition=render,short", "--time=1-0:05", "--mem=2G"] + \
                extra + [f"--output={os.path.join(logs, log)}"]
            for legacy in (False, True):
                self.assertEqual(sbatch_directives(text, legacy), expected)
        env = dict(os.environ, SLURM_ARRAY_TASK_ID="0")
        for task in ("0", "1"):
            run = subprocess.run(["bash", render], env=dict(env, SLURM_ARRAY_TASK_ID=task), capture_output=True,
                                 text=True, cwd=self.dir)
            self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        run = subprocess.run(["bash", finalize], capture_output=True, text=True, cwd=self.dir)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        with open(os.path.join(work, "verify.json")) as f:
            report = json.load(f)
        self.assertTrue(report["ok"], report)
        self.assertEqual(report["jobs"][0]["name"], job["name"])
        self.assertEqual(kiln_farm.read_exr_header(job["output"])["data_window"], [0, 0, 39, 9])
        self.assertEqual([os.path.join(d, n) for d, dirs, files in os.walk(self.dir) for n in dirs + files
                          if n.startswith("pwned")], [])
        # The dry run's sbatch lines are shell words too.
        rc, out, _ = self.submit_with_fake_slurm(["--plan", plan, "--kiln", kiln, "--work-dir", work, "--dry-run"])[:3]
        line = next(l for l in out.splitlines() if l.startswith("# sbatch --parsable --array"))
        self.assertEqual(shlex.split(line[2:])[-1], render)

    def test_files_in_the_work_folder_are_not_written_through_planted_links(self):
        # Someone who can write to the work folder plants links at the names the farm writes; each
        # write goes to a file of its own renamed into place, so the links' targets stay as they were.
        path = self.write_plan({"version": 1, "jobs": [self.job()]})
        work = os.path.join(self.dir, "work")
        os.makedirs(os.path.join(work, "status"))
        victim = os.path.join(self.dir, "victim")
        with open(victim, "w") as f:
            f.write("precious\n")
        names = ["tasks.txt", "packs.txt", "farm.json", "plan.json", "kiln_farm.py", "render.sbatch",
                 "finalize.sbatch", "submission.json", "verify.json.tmp"]
        for name in names:
            os.symlink(victim, os.path.join(work, name))
        rc, _, err, _ = self.submit_with_fake_slurm(["--plan", path, "--kiln", KILN, "--work-dir", work,
                                                     "--max-retries", "0", "--time", "5", "--mem", "1G"])
        self.assertEqual(rc, 0, err)
        with open(victim) as f:
            self.assertEqual(f.read(), "precious\n")
        # After submitting: the unit's status file and verify.json are written on the node.
        for name in ("status/0.rc", "verify.json", "verify.json.tmp"):
            if os.path.lexists(os.path.join(work, name)):
                os.remove(os.path.join(work, name))
            os.symlink(victim, os.path.join(work, name))
        run = subprocess.run(["bash", os.path.join(work, "render.sbatch")], capture_output=True, text=True,
                             env=dict(os.environ, SLURM_ARRAY_TASK_ID="0"))
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        rc, _, err = run_main(["finalize", "--work-dir", work])
        self.assertEqual(rc, 0, err)
        with open(victim) as f:
            self.assertEqual(f.read(), "precious\n")
        for name in names[:-1] + ["status/0.rc", "verify.json"]:
            self.assertFalse(os.path.islink(os.path.join(work, name)), name)
        self.assertEqual(sorted(n for n in os.listdir(work) if n.startswith(".")), [])  # no temporary left
        self.assertEqual(sorted(n for n in os.listdir(os.path.join(work, "status")) if n.startswith(".")), [])

    def test_header_reader_refuses_what_is_not_exr(self):
        path = os.path.join(self.dir, "x.exr")
        with open(path, "wb") as f:
            f.write(b"P6\n1 1\n255\n\0\0\0")
        with self.assertRaisesRegex(ValueError, "not an OpenEXR file"):
            kiln_farm.read_exr_header(path)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
