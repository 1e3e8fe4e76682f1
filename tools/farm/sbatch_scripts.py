"""The sbatch scripts of tools/farm/kiln_farm.py: the render array's and the stitch job's, their
#SBATCH lines with every value quoted as sbatch reads it, and --time and --mem as Slurm writes them.
kiln_farm.py copies this file into the work folder beside itself. Python 3 standard library only.
"""
import os
import re
import shlex


def shell_words(argv):
    return " ".join(shlex.quote(a) for a in argv)


def slurm_time(seconds):
    minutes = -(-int(seconds) // 60)
    return f"{minutes // 60:02d}:{minutes % 60:02d}:00"


def slurm_mem(peak_bytes):
    return f"{-(-peak_bytes // (1 << 20))}M"


def sbatch_value(text):
    """text as one argument of an #SBATCH line. sbatch splits those lines itself (no shell): at
    whitespace, with "..." and '...' grouping, a backslash taking the next character as it is and
    an unquoted # starting a comment (older Slurm: only "..." groups, and any # ends the line). A
    value with any of these goes in double quotes with \\ before each backslash, quote and #, which
    every version reads alike."""
    if text and not re.search(r"[\s\\\"'#]", text):
        return text
    return '"' + re.sub(r"([\\\"'#])", r"\\\1", text) + '"'


def slurm_file_name(path):
    """A path as a literal part of an --output file name pattern: % doubled."""
    return path.replace("%", "%%")


def sbatch_header(options, job_name, log_name, extra):
    """The #SBATCH lines: --time, --mem and --partition as check_submit_options let them through
    (nothing to quote), the job name and the log path quoted for sbatch."""
    lines = ["#!/bin/bash", f"#SBATCH --job-name={sbatch_value(job_name)}"]
    if options.partition:
        lines.append(f"#SBATCH --partition={options.partition}")
    lines += [f"#SBATCH --time={options.time}", f"#SBATCH --mem={options.mem}"]
    lines += [f"#SBATCH {e}" for e in extra]
    log = os.path.join(slurm_file_name(options.work_dir), "logs", log_name)
    lines.append(f"#SBATCH --output={sbatch_value(log)}")
    return lines


def array_option(options, task_count):
    throttle = f"%{options.array_limit}" if options.array_limit else ""
    return f"--array=0-{task_count - 1}{throttle}"


def render_script(options, task_count):
    """The script of every render array; task_count sizes the first one's #SBATCH --array, and
    submit passes each array's own --array and first task (KILN_FARM_FIRST_TASK)."""
    w = shlex.quote(options.work_dir)
    lines = sbatch_header(options, f"{options.job_name}-render", "render.%A_%a.log",
                          [array_option(options, task_count), f"--cpus-per-task={options.cpus_per_task}",
                           "--ntasks=1", "--nodes=1", "--requeue", "--open-mode=append"])
    lines += [
        "# Array task t renders the units on line t + 1 of packs.txt one after another; line u + 1 of",
        "# tasks.txt is unit u's kiln command (one band of one job). Each unit is retried, recorded",
        "# (status/UNIT.rc) and verified on its own; the task exits non-zero when any unit failed.",
        "# kiln writes the EXR atomically, so a failed or requeued attempt leaves no partial band.",
        "set -uo pipefail",
        f"work_dir={w}",
        f"max_retries={options.max_retries}",
        "# status/UNIT.rc goes through a new file of its own (noclobber: created exclusively, never",
        "# through a link planted there), renamed over the old one (mv -T: a planted folder or link",
        "# is not entered).",
        "record() {",
        '  local tmp',
        '  tmp=$(mktemp -u "$work_dir/status/.$1.rc.XXXXXXXXXX") &&',
        '    (set -C && echo "$2" >"$tmp") && mv -f -T "$tmp" "$work_dir/status/$1.rc" ||',
        '    echo "kiln farm: cannot record unit $1\'s exit status $2 in $work_dir/status" >&2',
        "}",
        'index="${SLURM_ARRAY_TASK_ID:?not an array task}"',
        'task=$((${KILN_FARM_FIRST_TASK:-0} + index))',
        'units=$(sed -n "$((task + 1))p" "$work_dir/packs.txt")',
        '[ -n "$units" ] || { echo "kiln farm: no line $((task + 1)) in $work_dir/packs.txt" >&2; exit 2; }',
        "failed=0",
        "for unit in $units; do",
        "  # A requeued task keeps the units an earlier run of it finished.",
        '  if [ "$(cat "$work_dir/status/$unit.rc" 2>/dev/null)" = 0 ]; then continue; fi',
        '  line=$(sed -n "$((unit + 1))p" "$work_dir/tasks.txt")',
        '  [ -n "$line" ] || { echo "kiln farm: no line $((unit + 1)) in $work_dir/tasks.txt" >&2; failed=2; continue; }',
        '  eval "argv=($line)"',
        "  attempt=0",
        "  while :; do",
        '    echo "kiln farm: task $task attempt $attempt (unit $unit) on $(hostname): ${argv[*]}"',
        '    "${argv[@]}"',
        "    rc=$?",
        '    record "$unit" "$rc"',
        '    [ "$rc" -eq 0 ] && break',
        "    # 2 is bad input or a usage error, the same on every attempt; 130/143 is a signal (scancel,",
        "    # the time limit), where Slurm decides. Anything else (1: I/O, a crash) is worth retrying.",
        '    case "$rc" in 130 | 143) exit "$rc" ;; esac',
        "    attempt=$((attempt + 1))",
        '    [ "$rc" -ne 2 ] && [ "$attempt" -le "$max_retries" ] || break',
        '    echo "kiln farm: unit $unit failed with exit $rc, retrying" >&2',
        "    sleep $((attempt * 5))",
        "  done",
        '  [ "$rc" -eq 0 ] || failed=$rc',
        "done",
        'exit "$failed"',
    ]
    return "\n".join(lines) + "\n"


def finalize_script(options):
    w = os.path.join(options.work_dir, "kiln_farm.py")
    lines = sbatch_header(options, f"{options.job_name}-stitch", "finalize.%j.log",
                          ["--cpus-per-task=1", "--ntasks=1", "--nodes=1"])
    lines += [
        "# Runs after every render task ended (afterany), stitches each job's bands into its output,",
        "# verifies every output and writes verify.json; exits 1 when anything is missing or wrong.",
        f"exec python3 {shell_words([w, 'finalize', '--work-dir', options.work_dir])}",
    ]
    return "\n".join(lines) + "\n"
