#!/usr/bin/env python3
"""Renders a kiln batch on a Slurm cluster: one array task per job and band, then a stitch job.

    kiln_farm.py submit (--plan PLAN.json | --manifest M --out-dir DIR) --work-dir W [options]
                        [-- extra kiln batch defaults]
    kiln_farm.py finalize --work-dir W     (what the stitch job runs: stitch, verify, verify.json)
    kiln_farm.py verify --work-dir W       (checks the outputs again, prints the report)

submit writes into W: plan.json (the resolved batch), tasks.txt (one shell-quoted kiln command a
line, line k is array task k: every job times every band), farm.json (what finalize needs),
render.sbatch and finalize.sbatch, and a copy of this script, so the jobs depend on W and the
kiln binary only. It submits render.sbatch as an array job and finalize.sbatch with
--dependency=afterany on it: finalize runs whether or not every task succeeded and reports each
missing band with its task's exit status and log. docs/farm.md describes the options.
Python 3 standard library only.
"""

import argparse
import json
import os
import re
import shlex
import shutil
import struct
import subprocess
import sys
import time

USAGE_ERROR = 2
TERMINAL_STATES = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY",
                   "PREEMPTED", "BOOT_FAIL", "DEADLINE"}
# Characters a band's file name keeps from its job's name; others become _ (the job index in front
# keeps two names that map alike apart).
FILE_NAME_UNSAFE = re.compile(r"[^A-Za-z0-9_.+-]")
CONTROL = re.compile(r"[\x00-\x1f\x7f]")


class InputError(Exception):
    """Bad input: reported as one line naming the file, the JSON path and the problem; exit 2."""


# ---------------------------------------------------------------------------------------------
# The plan: {"version": 1, "jobs": [{"name", "asset", "output", "render_args": [...]}]}


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
            if a in ("--band", "--tile", "--crop", "-o", "--output") or a.startswith(
                    ("--band=", "--tile=", "--crop=", "--output=")):
                raise InputError(f"{where}/render_args/{j}: '{a}' is set by the farm, not the plan")
        job["render_args"] = args
    return plan


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
# Work folder and sbatch scripts


def band_stem(index, job_name):
    """The file name stem of a job's bands: any name (spaces, slashes, any script) becomes a safe
    file name, numbered by the job's place in the plan so that it stays unique."""
    return f"{index:04d}-{FILE_NAME_UNSAFE.sub('_', job_name)[:80]}"


def tile_path(work_dir, stem, i, n):
    return os.path.join(work_dir, "tiles", f"{stem}.{i}of{n}.exr")


def build_tasks(plan, kiln, tiles, cpus_per_task, work_dir):
    """One task per job and band, in job order: (job name, band, kiln argv)."""
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


def sbatch_header(options, job_name, log_name, extra):
    lines = ["#!/bin/bash", f"#SBATCH --job-name={job_name}"]
    if options.partition:
        lines.append(f"#SBATCH --partition={options.partition}")
    lines += [f"#SBATCH --time={options.time}", f"#SBATCH --mem={options.mem}"]
    lines += [f"#SBATCH {e}" for e in extra]
    lines.append(f"#SBATCH --output={os.path.join(options.work_dir, 'logs', log_name)}")
    return lines


def render_script(options, task_count):
    throttle = f"%{options.array_limit}" if options.array_limit else ""
    w = shlex.quote(options.work_dir)
    lines = sbatch_header(options, f"{options.job_name}-render", "render.%A_%a.log",
                          [f"--array=0-{task_count - 1}{throttle}", f"--cpus-per-task={options.cpus_per_task}",
                           "--ntasks=1", "--nodes=1", "--requeue", "--open-mode=append"])
    lines += [
        "# One band of one job: line SLURM_ARRAY_TASK_ID + 1 of tasks.txt is its kiln command.",
        "# kiln writes the EXR atomically, so a failed or requeued attempt leaves no partial band.",
        "set -uo pipefail",
        f"work_dir={w}",
        f"max_retries={options.max_retries}",
        'task="${SLURM_ARRAY_TASK_ID:?not an array task}"',
        'line=$(sed -n "$((task + 1))p" "$work_dir/tasks.txt")',
        '[ -n "$line" ] || { echo "kiln farm: no line $((task + 1)) in $work_dir/tasks.txt" >&2; exit 2; }',
        'eval "argv=($line)"',
        "attempt=0",
        "while :; do",
        '  echo "kiln farm: task $task attempt $attempt on $(hostname): ${argv[*]}"',
        '  "${argv[@]}"',
        "  rc=$?",
        '  echo "$rc" >"$work_dir/status/$task.rc"',
        '  [ "$rc" -eq 0 ] && exit 0',
        "  # 2 is bad input or a usage error, the same on every attempt; 130/143 is a signal (scancel,",
        "  # the time limit), where Slurm decides. Anything else (1: I/O, a crash) is worth retrying.",
        '  case "$rc" in 2 | 130 | 143) exit "$rc" ;; esac',
        "  attempt=$((attempt + 1))",
        '  [ "$attempt" -le "$max_retries" ] || exit "$rc"',
        '  echo "kiln farm: task $task failed with exit $rc, retrying" >&2',
        "  sleep $((attempt * 5))",
        "done",
    ]
    return "\n".join(lines) + "\n"


def finalize_script(options):
    w = os.path.join(options.work_dir, "kiln_farm.py")
    lines = sbatch_header(options, f"{options.job_name}-stitch", "finalize.%j.log",
                          ["--cpus-per-task=1", "--ntasks=1", "--nodes=1"])
    lines += [
        "# Runs after every render task ended (afterany), stitches each job's bands into its output,",
        "# verifies every output and writes verify.json; exits 1 when anything is missing or wrong.",
        f"exec python3 {shlex.quote(w)} finalize --work-dir {shlex.quote(options.work_dir)}",
    ]
    return "\n".join(lines) + "\n"


def write_work_dir(options, plan, tasks):
    w = options.work_dir
    for sub in ("tiles", "logs", "status"):
        os.makedirs(os.path.join(w, sub), exist_ok=True)
    with open(os.path.join(w, "tasks.txt"), "w", encoding="utf-8") as f:
        for _, _, argv in tasks:
            f.write(" ".join(shlex.quote(a) for a in argv) + "\n")
    farm = {"version": 1, "kiln": options.kiln, "tiles": options.tiles, "jobs": []}
    for index, job in enumerate(plan["jobs"]):
        farm["jobs"].append({
            "name": job["name"], "asset": job["asset"], "output": job["output"],
            "width": option_value(job["render_args"], "--width"),
            "height": option_value(job["render_args"], "--height"),
            "tiles": [tile_path(w, band_stem(index, job["name"]), i, options.tiles) for i in range(options.tiles)],
            "tasks": [k for k, (name, _, _) in enumerate(tasks) if name == job["name"]],
        })
    with open(os.path.join(w, "farm.json"), "w", encoding="utf-8") as f:
        json.dump(farm, f, indent=2)
    with open(os.path.join(w, "plan.json"), "w", encoding="utf-8") as f:
        json.dump(plan, f, indent=2)
    shutil.copyfile(os.path.abspath(__file__), os.path.join(w, "kiln_farm.py"))
    # A band, status or report left by an earlier submission must not pass for this one's.
    for job in farm["jobs"]:
        for t in job["tiles"]:
            if os.path.exists(t):
                os.remove(t)
    for k in range(len(tasks)):
        p = os.path.join(w, "status", f"{k}.rc")
        if os.path.exists(p):
            os.remove(p)
    if os.path.exists(os.path.join(w, "verify.json")):
        os.remove(os.path.join(w, "verify.json"))
    for job in plan["jobs"]:
        os.makedirs(os.path.dirname(job["output"]), exist_ok=True)


def sbatch(args, cancel_on_failure=None):
    """Submits; on failure cancels cancel_on_failure (the array a finalize job would have ended)."""
    result = subprocess.run(["sbatch", "--parsable"] + args, capture_output=True, text=True)
    if result.returncode != 0:
        if cancel_on_failure:
            subprocess.run(["scancel", cancel_on_failure])
        sys.exit(f"kiln farm: sbatch {' '.join(args)} failed: {result.stderr.strip()}")
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
    plan_path = options.plan
    if options.manifest:
        os.makedirs(options.work_dir, exist_ok=True)
        if not options.out_dir:
            raise InputError("--manifest needs --out-dir")
        plan_path = os.path.join(options.work_dir, "plan.json")
        plan_from_manifest(options.kiln, os.path.abspath(options.manifest), os.path.abspath(options.out_dir),
                           options.batch_args, plan_path)
    elif options.batch_args:
        raise InputError("extra kiln batch defaults after -- need --manifest")
    plan = load_plan(plan_path)
    tasks = build_tasks(plan, options.kiln, options.tiles, options.cpus_per_task, options.work_dir)
    render = render_script(options, len(tasks))
    finalize = finalize_script(options)
    render_path = os.path.join(options.work_dir, "render.sbatch")
    finalize_path = os.path.join(options.work_dir, "finalize.sbatch")
    if options.dry_run:
        print(f"# {render_path}: {len(tasks)} tasks ({len(plan['jobs'])} jobs x {options.tiles} bands)")
        print(render)
        print(f"# {finalize_path}")
        print(finalize)
        print(f"# sbatch --parsable {render_path}")
        print(f"# sbatch --parsable --dependency=afterany:<render job id> --kill-on-invalid-dep=no {finalize_path}")
        return 0
    write_work_dir(options, plan, tasks)
    for path, text in ((render_path, render), (finalize_path, finalize)):
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    array_id = sbatch([render_path])
    final_id = sbatch([f"--dependency=afterany:{array_id}", "--kill-on-invalid-dep=no", finalize_path],
                      cancel_on_failure=array_id)
    with open(os.path.join(options.work_dir, "submission.json"), "w", encoding="utf-8") as f:
        json.dump({"render_job": array_id, "finalize_job": final_id, "tasks": len(tasks)}, f, indent=2)
    print(f"kiln farm: render array job {array_id} ({len(tasks)} tasks), finalize job {final_id}; "
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


def task_failure(work_dir, task):
    p = os.path.join(work_dir, "status", f"{task}.rc")
    try:
        with open(p, encoding="utf-8") as f:
            rc = f.read().strip()
    except OSError:
        rc = "never ran to the end (cancelled, timed out, node failure?)"
    return f"task {task}: exit {rc}; log {os.path.join(work_dir, 'logs', 'render.*_' + str(task) + '.log')}"


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
    for i, (tile, task) in enumerate(zip(job["tiles"], job["tasks"])):
        if not os.path.exists(tile):
            problems.append(f"band {i} of {n} missing ({task_failure(work_dir, task)})")
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
            shutil.move(job["tiles"][0], job["output"])
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
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(report, f, indent=2)
    os.replace(path + ".tmp", path)
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
    parser = argparse.ArgumentParser(prog="kiln_farm.py", description=__doc__.split("\n")[0])
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
    s.add_argument("--time", default="01:00:00", help="time limit per task, Slurm format (default 01:00:00)")
    s.add_argument("--cpus-per-task", type=positive_int, default=1, help="cores per task = kiln --threads")
    s.add_argument("--mem", default="2G", help="memory per task, Slurm format (default 2G)")
    s.add_argument("--max-retries", type=non_negative_int, default=1,
                   help="in-task retries of a failed render (default 1); Slurm requeues on node failure")
    s.add_argument("--array-limit", type=positive_int, help="at most N render tasks at once (%%N)")
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
