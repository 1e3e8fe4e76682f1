#!/usr/bin/env python3
"""Renders a kiln batch on a Slurm cluster: job arrays whose tasks each render one or more job bands,
then a stitch job.

    kiln_farm.py submit (--plan PLAN.json | --manifest M --out-dir DIR) --work-dir W [options]
                        [-- extra kiln batch defaults]
    kiln_farm.py finalize --work-dir W     (what the stitch job runs: stitch, verify, verify.json)
    kiln_farm.py verify --work-dir W       (checks the outputs again, prints the report)

submit writes into W: plan.json (the resolved batch), tasks.txt (one shell-quoted kiln command a
line, line u renders unit u: every job times every band), packs.txt (line t: the units task t
renders, one after another), farm.json (what finalize needs), render.sbatch (one script for every
array; each array passes its first task with --export) and finalize.sbatch, and copies of this
script and sbatch_scripts.py, so the jobs depend on W and the kiln binary only. The tasks are split
into as many arrays as the cluster's MaxArraySize needs; finalize.sbatch runs with
--dependency=afterany on all of them: whether or not every task succeeded, it reports each missing
band with its exit status and log. docs/farm.md describes the options.
Python 3 standard library only.
"""

import argparse
import errno
import json
import os
import re
import secrets
import shlex
import shutil
import struct
import subprocess
import sys
import time

from sbatch_scripts import (array_option, finalize_script, render_script, shell_words, slurm_mem,
                            slurm_time)

USAGE_ERROR = 2
TERMINAL_STATES = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY",
                   "PREEMPTED", "BOOT_FAIL", "DEADLINE"}
# Characters a band's file name keeps from its job's name; others become _ (the job index in front
# keeps two names that map alike apart).
FILE_NAME_UNSAFE = re.compile(r"[^A-Za-z0-9_.+-]")
CONTROL = re.compile(r"[\x00-\x1f\x7f]")
# What sbatch accepts for --time: minutes, minutes:seconds, hours:minutes:seconds, days-hours,
# days-hours:minutes, days-hours:minutes:seconds (or no limit); for --mem: a number with an optional
# K, M, G or T suffix (megabytes without); for --partition: one name or several, comma-separated.
SLURM_TIME = re.compile(r"(\d+(:\d+){0,2}|\d+-\d+(:\d+){0,2}|(?i:infinite|unlimited))\Z")
SLURM_MEM = re.compile(r"\d+[KMGTkmgt]?\Z")
SLURM_PARTITION = re.compile(r"[A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*\Z")


class InputError(Exception):
    """Bad input: reported as one line naming the file, the JSON path and the problem; exit 2."""


# ---------------------------------------------------------------------------------------------
# The plan: {"version": 1, "jobs": [{"name", "asset", "output", "render_args": [...],
#                                    "estimate": {"seconds", "peak_memory_bytes"} (optional)}]}


def load_plan(path):
    try:
        with open(path, encoding="utf-8") as f:
            plan = json.load(f)
    except OSError as e:
        raise InputError(f"{path}: cannot read: {e.strerror}")
    except json.JSONDecodeError as e:
        raise InputError(f"{path}: line {e.lineno}, column {e.colno}: {e.msg}")
    if not isinstance(plan, dict):
        raise InputError(f"{path}: /: expected an object")
    if plan.get("version") != 1:
        raise InputError(f"{path}: /version: expected 1, got {json.dumps(plan.get('version'))}")
    jobs = plan.get("jobs")
    if not isinstance(jobs, list) or not jobs:
        raise InputError(f"{path}: /jobs: expected a non-empty array")
    names, outputs = set(), set()
    for i, job in enumerate(jobs):
        where = f"{path}: /jobs/{i}"
        if not isinstance(job, dict):
            raise InputError(f"{where}: expected an object")
        for key in ("name", "asset", "output"):
            if not isinstance(job.get(key), str) or not job[key]:
                raise InputError(f"{where}/{key}: expected a non-empty string")
            # tasks.txt holds one shell-quoted command a line; any other character is quoted.
            if CONTROL.search(job[key]):
                raise InputError(f"{where}/{key}: {json.dumps(job[key])} contains a control character")
            if not encodable(job[key]):
                raise InputError(f"{where}/{key}: {json.dumps(job[key])} is not valid Unicode text")
        if job["name"] in names:
            raise InputError(f"{where}/name: '{job['name']}' is not unique")
        names.add(job["name"])
        for key in ("asset", "output"):
            if not os.path.isabs(job[key]):
                raise InputError(f"{where}/{key}: '{job[key]}' is not an absolute path")
        if job["output"] in outputs:
            raise InputError(f"{where}/output: '{job['output']}' is also another job's output")
        outputs.add(job["output"])
        args = job.get("render_args", [])
        if not isinstance(args, list) or not all(isinstance(a, str) for a in args):
            raise InputError(f"{where}/render_args: expected an array of strings")
        for j, a in enumerate(args):
            if "\n" in a or "\0" in a:
                raise InputError(f"{where}/render_args/{j}: contains a newline or NUL")
            if not encodable(a):
                raise InputError(f"{where}/render_args/{j}: is not valid Unicode text")
            if a in ("--band", "--tile", "--crop", "-o", "--output") or a.startswith(
                    ("--band=", "--tile=", "--crop=", "--output=")):
                raise InputError(f"{where}/render_args/{j}: '{a}' is set by the farm, not the plan")
        job["render_args"] = args
        if "estimate" in job:  # written by kiln batch --plan-only: sizes --time, --mem and the packing
            e = job["estimate"]
            for key in ("seconds", "peak_memory_bytes", "load_seconds", "render_seconds"):
                if key.endswith("_seconds") and isinstance(e, dict) and key not in e:
                    continue  # optional: a plan written by hand may give seconds alone
                value = e.get(key) if isinstance(e, dict) else None
                if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value < 1e18:
                    raise InputError(f"{where}/estimate/{key}: expected a non-negative number")
    return plan


def encodable(text):
    """Whether text can be written as UTF-8 (a name read from a non-UTF-8 command line or a JSON
    lone surrogate cannot)."""
    try:
        text.encode("utf-8")
        return True
    except UnicodeEncodeError:
        return False


def check_submit_options(options):
    """Refuses, as an InputError naming the option, every value that would reach a generated
    script, tasks.txt or an #SBATCH line and that Slurm or the scripts cannot hold: one line, before
    anything is written or submitted. What passes is quoted where it is written (shlex.quote in the
    shell lines, sbatch_value in the #SBATCH lines)."""
    def refuse(option, value, problem):
        raise InputError(f"{option} {json.dumps(value)}: {problem}")

    def text(option, value):
        if "\n" in value:
            refuse(option, value, "contains a newline (each line of the generated scripts is a command)")
        if CONTROL.search(value):
            refuse(option, value, "contains a control character")
        if not encodable(value):
            refuse(option, value, "is not valid Unicode text")

    for option, value in (("--work-dir", options.work_dir), ("--kiln", options.kiln),
                          ("--out-dir", options.out_dir), ("--job-name", options.job_name),
                          ("--time", options.time), ("--mem", options.mem), ("--partition", options.partition)):
        if value is not None:
            text(option, value)
    for value in options.batch_args:
        text("kiln batch default", value)
    if not options.job_name:
        refuse("--job-name", options.job_name, "is empty")
    if not options.job_name.isprintable():
        refuse("--job-name", options.job_name, "contains a character that is not printable")
    # slurmd drops every backslash of an --output path and then leaves its %A/%a/%j unexpanded.
    if "\\" in options.work_dir:
        refuse("--work-dir", options.work_dir, "contains a backslash, which Slurm's --output log paths cannot hold")
    if options.time is not None and not SLURM_TIME.match(options.time):
        refuse("--time", options.time, "not a Slurm time (minutes, minutes:seconds, hours:minutes:seconds, "
               "days-hours, days-hours:minutes, days-hours:minutes:seconds or UNLIMITED)")
    if options.mem is not None and not SLURM_MEM.match(options.mem):
        refuse("--mem", options.mem, "not a Slurm memory size (a whole number, megabytes, or with a K, M, G "
               "or T suffix)")
    if options.partition is not None and not SLURM_PARTITION.match(options.partition):
        refuse("--partition", options.partition, "not a Slurm partition name (letters, digits, _ . -; "
               "several separated by commas)")


def option_value(args, name):
    """The last value of `--name V` or `--name=V` in a kiln argument list, or None."""
    value = None
    for i, a in enumerate(args):
        if a == name and i + 1 < len(args):
            value = args[i + 1]
        elif a.startswith(name + "="):
            value = a[len(name) + 1:]
    return value


def batch_supports_plan_only(kiln):
    """kiln batch --help names --plan-only once the batch command can write plans."""
    try:
        out = subprocess.run([kiln, "batch", "--help"], capture_output=True, text=True, timeout=60)
    except OSError:
        return False
    return "--plan-only" in out.stdout + out.stderr


def plan_from_manifest(kiln, manifest, out_dir, extra, plan_path):
    if not batch_supports_plan_only(kiln):
        raise InputError(f"{kiln}: 'kiln batch --plan-only' is not supported by this binary; "
                         "pass --plan PLAN.json instead")
    cmd = [kiln, "batch", "--manifest", manifest, "--out-dir", out_dir, "--plan-only", plan_path] + extra
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stderr.write(result.stderr)
        raise InputError(f"{manifest}: kiln batch --plan-only exited {result.returncode}")


# ---------------------------------------------------------------------------------------------
# Writing into folders others may write to


def exclusive_temporary(path):
    """Creates a new file beside path, under a name of its own (.NAME.kiln-farm-tmp-PID-RANDOM),
    exclusively: whatever was planted at any name (a link, a file) is never opened. Returns the
    open binary file and its name."""
    folder, name = os.path.split(path)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    while True:
        temporary = os.path.join(folder, f".{name}.kiln-farm-tmp-{os.getpid()}-{secrets.token_hex(6)}")
        try:
            return os.fdopen(os.open(temporary, flags, 0o666), "wb"), temporary
        except FileExistsError:
            continue


def replace_file(path, fill):
    """Writes path whole: fill(binary file) writes a temporary file of its own, which then
    replaces path by rename (a link planted at path is replaced, not written through; a reader
    sees the old file or the new one)."""
    f, temporary = exclusive_temporary(path)
    try:
        with f:
            fill(f)
        os.replace(temporary, path)
    except BaseException:
        try:
            os.unlink(temporary)
        except OSError:
            pass
        raise


def write_text(path, text):
    replace_file(path, lambda f: f.write(text.encode("utf-8")))


def write_json(path, value):
    write_text(path, json.dumps(value, indent=2))


def move_file(source, target):
    """Renames source to target; across filesystems, copies it through a temporary file of its
    own beside target, renamed into place, then removes source."""
    try:
        os.replace(source, target)
        return
    except OSError as e:
        if e.errno != errno.EXDEV:
            raise
    with open(source, "rb") as src:
        replace_file(target, lambda f: shutil.copyfileobj(src, f, 1 << 20))
    os.remove(source)


# ---------------------------------------------------------------------------------------------
# Work folder and task list (the sbatch scripts: sbatch_scripts.py)


def band_stem(index, job_name):
    """The file name stem of a job's bands: any name (spaces, slashes, any script) becomes a safe
    file name, numbered by the job's place in the plan so that it stays unique."""
    return f"{index:04d}-{FILE_NAME_UNSAFE.sub('_', job_name)[:80]}"


def tile_path(work_dir, stem, i, n):
    return os.path.join(work_dir, "tiles", f"{stem}.{i}of{n}.exr")


def build_tasks(plan, kiln, tiles, cpus_per_task, work_dir):
    """One unit (a kiln command) per job and band, in job order: (job name, band, kiln argv).
    Line u of tasks.txt is unit u; packs.txt groups units into array tasks."""
    tasks = []
    for index, job in enumerate(plan["jobs"]):
        args = list(job["render_args"])
        # Without cgroups nothing stops kiln from starting one thread per core of the node.
        if option_value(args, "--threads") is None:
            args += ["--threads", str(cpus_per_task)]
        for i in range(tiles):
            band = ["--band", f"{i}/{tiles}"] if tiles > 1 else []
            tile = tile_path(work_dir, band_stem(index, job["name"]), i, tiles)
            argv = [kiln, "render", job["asset"], "-o", tile] + band + args
            tasks.append((job["name"], i, argv))
    return tasks


# ---------------------------------------------------------------------------------------------
# Estimates, packing units into tasks, and tasks into arrays

DEFAULT_MAX_ARRAY_SIZE = 1001  # Slurm's default MaxArraySize
# --time and --mem from the plan's estimates: the estimate times these factors (they cover the
# probe's error on the shared assets, docs/farm.md), plus what every kiln process costs anyway.
TIME_SAFETY, MEMORY_SAFETY = 3.0, 1.5
TASK_START_SECONDS, TASK_MIN_SECONDS = 30, 300
PROCESS_BYTES = 256 << 20


def job_estimate(job, threads):
    """(load seconds, render seconds on `threads` threads, peak bytes) of a plan job's "estimate",
    or None when it has none. kiln batch --plan-only writes load_seconds (load and BVH build) and
    render_seconds on one thread; a plain "seconds" is taken as the render's."""
    e = job.get("estimate")
    if not isinstance(e, dict):
        return None
    if "render_seconds" in e:
        return float(e.get("load_seconds", 0.0)), float(e["render_seconds"]) / threads, int(e["peak_memory_bytes"])
    return 0.0, float(e["seconds"]), int(e["peak_memory_bytes"])


def unit_estimates(plan, tiles, cpus_per_task):
    """Estimated seconds and bytes of each unit: a band renders 1/tiles of its job's pixels but
    loads the whole scene. A job without an estimate (its asset could not be probed) counts as the
    largest of the others; None when no job has one."""
    estimates = []
    for job in plan["jobs"]:
        threads = option_value(job["render_args"], "--threads")
        estimates.append(job_estimate(job, max(1, int(threads)) if threads and threads.isdigit() and threads != "0"
                                      else cpus_per_task))
    known = [e for e in estimates if e is not None]
    if not known:
        return None
    fallback = tuple(max(e[k] for e in known) for k in range(3))
    units = []
    for e in estimates:
        load, render, peak = e or fallback
        units += [(load + render / tiles, peak)] * tiles
    return units


def pack_units(unit_count, estimates, jobs_per_task, task_seconds, target_tasks):
    """Groups consecutive units into array tasks, a list of unit lists: jobs_per_task units a task
    when given; else, with estimates, as many as fit in task_seconds (a longer unit alone); else
    as many a task as keep the count within target_tasks."""
    if not jobs_per_task and estimates:
        packs, seconds = [], 0.0
        for unit, (unit_seconds, _) in enumerate(estimates):
            if not packs or seconds + unit_seconds > task_seconds:
                packs.append([])
                seconds = 0.0
            packs[-1].append(unit)
            seconds += unit_seconds
        return packs
    size = jobs_per_task or -(-unit_count // target_tasks)
    return [list(range(u, min(u + size, unit_count))) for u in range(0, unit_count, size)]


def split_arrays(task_count, max_array_size):
    """Array jobs as (first task, task count): indices 0..n-1 of one array must stay below
    MaxArraySize, so an array holds at most MaxArraySize tasks."""
    return [(first, min(max_array_size, task_count - first)) for first in range(0, task_count, max_array_size)]


def cluster_max_array_size():
    """MaxArraySize from `scontrol show config`; Slurm's default when it cannot be read."""
    try:
        result = subprocess.run(["scontrol", "show", "config"], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return DEFAULT_MAX_ARRAY_SIZE
    m = re.search(r"^MaxArraySize\s*=\s*(\d+)\s*$", result.stdout, re.M)
    if result.returncode != 0 or not m or int(m.group(1)) < 1:
        return DEFAULT_MAX_ARRAY_SIZE
    return int(m.group(1))


def size_resources(options, estimates, packs):
    """Fills --time and --mem the user left open: from the estimates (the longest task's units one
    after another, 1 + max-retries times; the largest unit's peak), else the fixed defaults."""
    if options.time is None:
        if estimates:
            longest = max(sum(estimates[u][0] for u in pack) for pack in packs)
            options.time = slurm_time(max(TASK_MIN_SECONDS, TASK_START_SECONDS * len(max(packs, key=len)) +
                                          TIME_SAFETY * longest * (1 + options.max_retries)))
        else:
            options.time = "01:00:00"
    if options.mem is None:
        if estimates:
            options.mem = slurm_mem(PROCESS_BYTES + int(MEMORY_SAFETY * max(peak for _, peak in estimates)))
        else:
            options.mem = "2G"


def write_work_dir(options, plan, tasks, packs=None, arrays=None):
    w = options.work_dir
    packs = packs or [[u] for u in range(len(tasks))]
    arrays = arrays or [(0, len(packs))]
    for sub in ("tiles", "logs", "status"):
        os.makedirs(os.path.join(w, sub), exist_ok=True)
    # Every file goes through a temporary file of its own renamed into place (replace_file).
    write_text(os.path.join(w, "tasks.txt"), "".join(shell_words(argv) + "\n" for _, _, argv in tasks))
    write_text(os.path.join(w, "packs.txt"), "".join(" ".join(str(u) for u in pack) + "\n" for pack in packs))
    task_of = {u: t for t, pack in enumerate(packs) for u in pack}
    farm = {"version": 1, "kiln": options.kiln, "tiles": options.tiles,
            "arrays": [{"first_task": first, "tasks": count} for first, count in arrays], "jobs": []}
    for index, job in enumerate(plan["jobs"]):
        units = [u for u, (name, _, _) in enumerate(tasks) if name == job["name"]]
        farm["jobs"].append({
            "name": job["name"], "asset": job["asset"], "output": job["output"],
            "width": option_value(job["render_args"], "--width"),
            "height": option_value(job["render_args"], "--height"),
            "tiles": [tile_path(w, band_stem(index, job["name"]), i, options.tiles) for i in range(options.tiles)],
            "units": units, "tasks": [task_of[u] for u in units],
        })
    write_json(os.path.join(w, "farm.json"), farm)
    write_json(os.path.join(w, "plan.json"), plan)
    # The finalize job runs these copies: kiln_farm.py imports its sbatch scripts module.
    here = os.path.dirname(os.path.abspath(__file__))
    for name in ("kiln_farm.py", "sbatch_scripts.py"):
        with open(os.path.join(here, name), "rb") as source:
            replace_file(os.path.join(w, name), lambda f: shutil.copyfileobj(source, f))
    # A band, status or report left by an earlier submission must not pass for this one's (nor a
    # link planted in its place).
    for job in farm["jobs"]:
        for t in job["tiles"]:
            if os.path.lexists(t):
                os.remove(t)
    for name in os.listdir(os.path.join(w, "status")):
        if name.endswith(".rc"):
            os.remove(os.path.join(w, "status", name))
    for name in ("verify.json", "submission.json"):
        if os.path.lexists(os.path.join(w, name)):
            os.remove(os.path.join(w, name))
    for job in plan["jobs"]:
        os.makedirs(os.path.dirname(job["output"]), exist_ok=True)


def sbatch(args, cancel_on_failure=()):
    """Submits; on failure cancels cancel_on_failure (the arrays submitted before it, which no
    finalize job would end)."""
    result = subprocess.run(["sbatch", "--parsable"] + args, capture_output=True, text=True)
    if result.returncode != 0:
        if cancel_on_failure:
            subprocess.run(["scancel"] + list(cancel_on_failure))
        sys.exit(f"kiln farm: sbatch {shell_words(args)} failed: {result.stderr.strip()}")
    return result.stdout.strip().split(";")[0]


def job_state(job_id):
    """The job's state from scontrol (no accounting needed), or None once Slurm forgot it."""
    result = subprocess.run(["scontrol", "show", "job", "-o", job_id], capture_output=True, text=True)
    m = re.search(r"\bJobState=(\S+)", result.stdout)
    return m.group(1) if result.returncode == 0 and m else None


def wait_for(job_id, work_dir, poll_seconds=2.0):
    while True:
        state = job_state(job_id)
        if state is None:  # ended longer than MinJobAge ago: verify.json tells how it went
            report = os.path.join(work_dir, "verify.json")
            try:
                with open(report, encoding="utf-8") as f:
                    return "COMPLETED" if json.load(f).get("ok") else "FAILED"
            except (OSError, ValueError):
                return "UNKNOWN"
        if state in TERMINAL_STATES:
            return state
        time.sleep(poll_seconds)


def submit(options):
    options.work_dir = os.path.abspath(options.work_dir)
    options.kiln = os.path.abspath(options.kiln)
    check_submit_options(options)
    plan_path = options.plan
    if options.manifest:
        os.makedirs(options.work_dir, exist_ok=True)
        if not options.out_dir:
            raise InputError("--manifest needs --out-dir")
        plan_path = os.path.join(options.work_dir, "plan.json")
        # Estimates cost each asset a load and a probe render; leave them out when nothing uses them.
        uses_estimates = not (options.time and options.mem and options.jobs_per_task)
        plan_from_manifest(options.kiln, os.path.abspath(options.manifest), os.path.abspath(options.out_dir),
                           ([] if uses_estimates else ["--no-estimates"]) + options.batch_args, plan_path)
    elif options.batch_args:
        raise InputError("extra kiln batch defaults after -- need --manifest")
    plan = load_plan(plan_path)
    tasks = build_tasks(plan, options.kiln, options.tiles, options.cpus_per_task, options.work_dir)
    estimates = unit_estimates(plan, options.tiles, options.cpus_per_task)
    packs = pack_units(len(tasks), estimates, options.jobs_per_task, options.task_seconds, options.target_tasks)
    size_resources(options, estimates, packs)
    max_array_size = options.max_array_size or cluster_max_array_size()
    arrays = split_arrays(len(packs), max_array_size)
    render = render_script(options, arrays[0][1])
    finalize = finalize_script(options)
    render_path = os.path.join(options.work_dir, "render.sbatch")
    finalize_path = os.path.join(options.work_dir, "finalize.sbatch")
    array_args = [[array_option(options, count), f"--export=ALL,KILN_FARM_FIRST_TASK={first}", render_path]
                  for first, count in arrays]
    summary = (f"{len(tasks)} units ({len(plan['jobs'])} jobs x {options.tiles} bands) in {len(packs)} tasks "
               f"(at most {max(len(p) for p in packs)} units a task) in {len(arrays)} arrays "
               f"(MaxArraySize {max_array_size}); --time {options.time} --mem {options.mem}")
    if options.dry_run:
        print(f"# {render_path}: {summary}")
        print(render)
        print(f"# {finalize_path}")
        print(finalize)
        for args in array_args:
            print(f"# sbatch --parsable {shell_words(args)}")
        dependency = ":".join(f"<render job id {i}>" for i in range(len(arrays)))
        print(f"# sbatch --parsable --dependency=afterany:{dependency} --kill-on-invalid-dep=no "
              f"{shlex.quote(finalize_path)}")
        return 0
    write_work_dir(options, plan, tasks, packs, arrays)
    for path, text in ((render_path, render), (finalize_path, finalize)):
        write_text(path, text)
    array_ids = []
    for args in array_args:
        array_ids.append(sbatch(args, cancel_on_failure=array_ids))
    final_id = sbatch([f"--dependency=afterany:{':'.join(array_ids)}", "--kill-on-invalid-dep=no", finalize_path],
                      cancel_on_failure=array_ids)
    write_json(os.path.join(options.work_dir, "submission.json"),
               {"render_job": array_ids[0], "render_jobs": array_ids, "finalize_job": final_id,
                "tasks": len(packs), "units": len(tasks), "max_array_size": max_array_size})
    print(f"kiln farm: render array jobs {' '.join(array_ids)}: {summary}; finalize job {final_id}; "
          f"report: {os.path.join(options.work_dir, 'verify.json')}")
    if not options.wait:
        return 0
    state = wait_for(final_id, options.work_dir)
    print(f"kiln farm: finalize job {final_id} {state}")
    return 0 if state == "COMPLETED" else 1


# ---------------------------------------------------------------------------------------------
# EXR headers (single-part scanline files, what kiln writes), read with the standard library

LINES_PER_CHUNK = {0: 1, 1: 1, 2: 1, 3: 16, 4: 32, 5: 16, 6: 32, 7: 32, 8: 32, 9: 256}
PIXEL_TYPES = {0: "uint", 1: "half", 2: "float"}


def read_exr_header(path):
    """Display and data windows and channels of an EXR; raises ValueError when it is not a
    complete single-part scanline EXR (every chunk in the offset table must lie inside the file)."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 8 or data[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    flags = struct.unpack_from("<I", data, 4)[0]
    if flags & 0x1a00:
        raise ValueError("tiled, deep or multi-part EXR")
    pos, attrs = 8, {}

    def cstring(at):
        end = data.index(b"\0", at)
        return data[at:end].decode("latin-1"), end + 1

    try:
        while data[pos] != 0:
            name, pos = cstring(pos)
            kind, pos = cstring(pos)
            size = struct.unpack_from("<i", data, pos)[0]
            pos += 4
            attrs[name] = (kind, data[pos:pos + size])
            pos += size
        pos += 1
    except (IndexError, ValueError, struct.error):
        raise ValueError("truncated header")
    for needed in ("channels", "compression", "dataWindow", "displayWindow"):
        if needed not in attrs:
            raise ValueError(f"no {needed} attribute")
    box = lambda raw: struct.unpack("<4i", raw[:16])
    data_window, display_window = box(attrs["dataWindow"][1]), box(attrs["displayWindow"][1])
    channels, raw, at = [], attrs["channels"][1], 0
    while at < len(raw) and raw[at] != 0:
        end = raw.index(b"\0", at)
        name = raw[at:end].decode("latin-1")
        pixel_type = struct.unpack_from("<i", raw, end + 1)[0]
        channels.append(f"{name}:{PIXEL_TYPES.get(pixel_type, str(pixel_type))}")
        at = end + 1 + 16
    compression = attrs["compression"][1][0]
    if compression not in LINES_PER_CHUNK:
        raise ValueError(f"unknown compression {compression}")
    rows = data_window[3] - data_window[1] + 1
    chunks = -(-rows // LINES_PER_CHUNK[compression])
    for k in range(chunks):
        try:
            offset = struct.unpack_from("<Q", data, pos + 8 * k)[0]
            y, size = struct.unpack_from("<ii", data, offset)
        except struct.error:
            raise ValueError(f"chunk {k} of {chunks} lies outside the file (truncated?)")
        if not data_window[1] <= y <= data_window[3] or offset + 8 + size > len(data):
            raise ValueError(f"chunk {k} of {chunks} is damaged or truncated")
    return {"display_window": list(display_window), "data_window": list(data_window), "channels": channels}


# ---------------------------------------------------------------------------------------------
# finalize: stitch the bands, verify every output, write verify.json


def band_rows(i, n, height):
    """Rows [y0, y1) of band i of n, as kiln render --band computes them."""
    return i * height // n, (i + 1) * height // n


def task_log(work_dir, farm, task):
    """The Slurm log of a task: render.ARRAYID_INDEX.log, the id from submission.json when there."""
    arrays = farm.get("arrays") or [{"first_task": 0, "tasks": task + 1}]
    number = next((k for k, a in enumerate(arrays) if a["first_task"] <= task < a["first_task"] + a["tasks"]), 0)
    array_id = "*"
    try:
        with open(os.path.join(work_dir, "submission.json"), encoding="utf-8") as f:
            array_id = json.load(f).get("render_jobs", ["*"])[number]
    except (OSError, ValueError, IndexError):
        pass
    return os.path.join(work_dir, "logs", f"render.{array_id}_{task - arrays[number]['first_task']}.log")


def task_failure(work_dir, farm, unit, task):
    p = os.path.join(work_dir, "status", f"{unit}.rc")
    try:
        with open(p, encoding="utf-8") as f:
            rc = f.read().strip()
    except OSError:
        rc = "never ran to the end (cancelled, timed out, node failure?)"
    return f"task {task}: exit {rc}; log {task_log(work_dir, farm, task)}"


def expected_size(job, header):
    width, height = header["display_window"][2] + 1, header["display_window"][3] + 1
    problems = []
    for key, actual in (("width", width), ("height", height)):
        if job[key] is not None and str(actual) != str(job[key]):
            problems.append(f"display window {key} {actual}, the plan asks for {job[key]}")
    return width, height, problems


def verify_output(job, problems):
    """Checks a job's finished output: readable, display window the planned size, data window the
    full frame. Appends problems; returns the header or None."""
    try:
        header = read_exr_header(job["output"])
    except OSError as e:
        problems.append(f"output {job['output']}: {e.strerror}")
        return None
    except ValueError as e:
        problems.append(f"output {job['output']}: {e}")
        return None
    _, _, size_problems = expected_size(job, header)
    problems += size_problems
    if header["display_window"][:2] != [0, 0]:
        problems.append(f"display window {header['display_window']} does not start at 0,0")
    if header["data_window"] != header["display_window"]:
        problems.append(f"data window {header['data_window']} is not the full frame {header['display_window']}")
    return header


def finalize_job(farm, job, work_dir):
    problems, n = [], farm["tiles"]
    headers = []
    units = job.get("units", job["tasks"])  # a farm.json from before packing: one unit a task
    for i, (tile, unit, task) in enumerate(zip(job["tiles"], units, job["tasks"])):
        if not os.path.exists(tile):
            problems.append(f"band {i} of {n} missing ({task_failure(work_dir, farm, unit, task)})")
            continue
        try:
            header = read_exr_header(tile)
        except (OSError, ValueError) as e:
            problems.append(f"band {i} of {n} {tile}: {e}")
            continue
        width, height, size_problems = expected_size(job, header)
        problems += size_problems
        y0, y1 = band_rows(i, n, height)
        if header["data_window"] != [0, y0, width - 1, y1 - 1]:
            problems.append(f"band {i} of {n} has data window {header['data_window']}, expected "
                            f"{[0, y0, width - 1, y1 - 1]}")
        headers.append(header)
    if not problems:
        if n == 1:
            try:
                move_file(job["tiles"][0], job["output"])
            except OSError as e:
                problems.append(f"cannot move {job['tiles'][0]} to the output: {e.strerror}")
        else:
            result = subprocess.run([farm["kiln"], "stitch", job["output"]] + job["tiles"],
                                    capture_output=True, text=True)
            if result.returncode != 0:
                problems.append(f"kiln stitch exited {result.returncode}: {result.stderr.strip()}")
    header = verify_output(job, problems) if not problems else None
    report = {"name": job["name"], "output": job["output"], "ok": not problems, "problems": problems}
    if header:
        report.update(width=header["display_window"][2] + 1, height=header["display_window"][3] + 1,
                      channels=header["channels"])
    return report


def write_report(work_dir, reports):
    report = {"ok": all(r["ok"] for r in reports), "jobs": reports}
    path = os.path.join(work_dir, "verify.json")
    write_json(path, report)
    for r in reports:
        for p in r["problems"]:
            print(f"kiln farm: {r['name']}: {p}", file=sys.stderr)
    good = sum(r["ok"] for r in reports)
    print(f"kiln farm: {good} of {len(reports)} outputs verified; {path}")
    return 0 if report["ok"] else 1


def load_farm(work_dir):
    path = os.path.join(work_dir, "farm.json")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise InputError(f"{path}: cannot read the farm description: {e}")


def finalize(options):
    work_dir = os.path.abspath(options.work_dir)
    farm = load_farm(work_dir)
    return write_report(work_dir, [finalize_job(farm, job, work_dir) for job in farm["jobs"]])


def verify(options):
    work_dir = os.path.abspath(options.work_dir)
    reports = []
    for job in load_farm(work_dir)["jobs"]:
        problems = []
        header = verify_output(job, problems)
        r = {"name": job["name"], "output": job["output"], "ok": not problems, "problems": problems}
        if header:
            r["channels"] = header["channels"]
        reports.append(r)
    return write_report(work_dir, reports)


# ---------------------------------------------------------------------------------------------


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text} is not a positive integer")
    return value


def non_negative_int(text):
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text} is negative")
    return value


def parse_args(argv):
    parser = argparse.ArgumentParser(prog="kiln_farm.py", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    s = commands.add_parser("submit", help="write the task list and sbatch scripts, submit them")
    source = s.add_mutually_exclusive_group(required=True)
    source.add_argument("--plan", help="resolved batch plan (kiln batch --plan-only format)")
    source.add_argument("--manifest", help="batch manifest; kiln batch --plan-only resolves it")
    s.add_argument("--out-dir", help="output folder for --manifest")
    s.add_argument("--kiln", default="build/renderer/app/kiln", help="kiln binary, on a shared filesystem")
    s.add_argument("--work-dir", required=True, help="task list, bands, logs, verify.json (shared filesystem)")
    s.add_argument("--tiles", type=positive_int, default=1, help="horizontal bands per job (1 = whole frames)")
    s.add_argument("--partition", help="Slurm partition (default: the cluster's default)")
    s.add_argument("--time", help="time limit per task, Slurm format (default: from the plan's estimates, "
                   "else 01:00:00)")
    s.add_argument("--cpus-per-task", type=positive_int, default=1, help="cores per task = kiln --threads")
    s.add_argument("--mem", help="memory per task, Slurm format (default: from the plan's estimates, else 2G)")
    s.add_argument("--max-retries", type=non_negative_int, default=1,
                   help="in-task retries of a failed render (default 1); Slurm requeues on node failure")
    s.add_argument("--array-limit", type=positive_int, help="at most N render tasks of each array at once (%%N)")
    s.add_argument("--jobs-per-task", type=positive_int,
                   help="units (job bands) rendered one after another by one array task (default: by the "
                        "estimates, else as many as keep the tasks within --target-tasks)")
    s.add_argument("--task-seconds", type=float, default=300.0,
                   help="with estimates and no --jobs-per-task: pack units into tasks of about this many "
                        "estimated render seconds (default 300)")
    s.add_argument("--target-tasks", type=positive_int, default=500,
                   help="without estimates and --jobs-per-task: at most this many tasks (default 500)")
    s.add_argument("--max-array-size", type=positive_int,
                   help="the cluster's MaxArraySize (default: from scontrol show config, else 1001)")
    s.add_argument("--job-name", default="kiln", help="Slurm job name prefix (default kiln)")
    s.add_argument("--wait", action="store_true", help="block until the finalize job ends; exit 0 if COMPLETED")
    s.add_argument("--dry-run", action="store_true", help="print the sbatch scripts, submit nothing")
    s.add_argument("batch_args", nargs="*", help="after --: extra kiln batch defaults (with --manifest)")
    for name, helptext in (("finalize", "stitch, verify and write verify.json (the stitch job)"),
                           ("verify", "verify the outputs again and rewrite verify.json")):
        c = commands.add_parser(name, help=helptext)
        c.add_argument("--work-dir", required=True)
    return parser.parse_args(argv)


def main(argv):
    options = parse_args(argv)
    try:
        return {"submit": submit, "finalize": finalize, "verify": verify}[options.command](options)
    except InputError as e:
        print(f"kiln farm: {e}", file=sys.stderr)
        return USAGE_ERROR


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
