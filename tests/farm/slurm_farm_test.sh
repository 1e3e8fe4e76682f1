#!/usr/bin/env bash
# Renders a small batch on a private single-node Slurm through tools/farm/kiln_farm.py and checks
# every stitched output against a single-process `kiln render` of the same job: the same channel
# names and formats, the full frame as data window, and pixels equal under `idiff` with zero
# tolerance. A second submission, through a kiln wrapper that fails each band's first attempt,
# checks that a failed render is retried, that a job whose asset is missing is not retried and is
# reported in verify.json (band missing, exit 2) with the finalize job failing. The cluster's
# MaxArraySize is 5, so every submission of more than 5 tasks is split into several arrays; a batch
# of 40 small jobs (and one missing asset) is packed 3 jobs a task: 14 tasks in 3 arrays, each job
# verified on its own. A work folder, asset, output, kiln path and job name full of spaces, quotes,
# $(...), backticks, # and % go through sbatch intact and run none of what they hold. When
# `kiln batch --help` offers --plan-only, a submission goes through --manifest.
# Needs root (it starts munged, slurmctld and slurmd); exits 77 (skipped) otherwise.
# Usage: slurm_farm_test.sh SOURCE_DIR KILN_BINARY
set -euo pipefail
source_dir=$(cd "$1" && pwd)
kiln=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
farm="$source_dir/tools/farm"

if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: the Slurm farm test starts slurmd and munged and must run as root"
  exit 77
fi
"$farm/install_test_slurm.sh"

scratch=$(mktemp -d /tmp/kiln-farm-test.XXXXXX)
chmod 755 "$scratch"  # munged wants every folder above its socket searchable by all
cleanup() {
  local rc=$?
  "$farm/test_slurm.sh" stop "$scratch/slurm" || rc=1
  rm -rf "$scratch"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 143' TERM  # so that an interrupted run also stops its daemons
trap 'exit 130' INT
slurm_env=$(KILN_TEST_SLURM_MAX_ARRAY_SIZE=5 "$farm/test_slurm.sh" start "$scratch/slurm")  # a plain assignment, so set -e sees a failure
eval "$slurm_env"

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# A band boundary cuts through each picture: a wide filter (its reach crosses bands), AOVs,
# float channels, an environment map, a mirror and glass.
scenes="$source_dir/scenes"
size=(--width 96 --height 64)
write_plan() {  # write_plan PLAN OUT_DIR JOB...; a job is "name|asset|arg arg ..."
  python3 - "$@" <<'PY'
import json, sys
plan, out_dir, jobs = sys.argv[1], sys.argv[2], []
for spec in sys.argv[3:]:
    name, asset, args = spec.split("|")
    jobs.append({"name": name, "asset": asset, "output": f"{out_dir}/{name}.exr",
                 "render_args": args.split()})
json.dump({"version": 1, "jobs": jobs}, open(plan, "w"), indent=2)
PY
}
glass_args="--spp 1 --float --environment $scenes/glass_showcase_sky.hdr --show-background"
jobs=(
  "cornell|$scenes/cornell_box.gltf|${size[*]} --spp 4 --filter gaussian --aovs beauty,Z,N,P,albedo,uv,id"
  "quadrics|$scenes/quadric_showcase.gltf|${size[*]} --spp 2 --filter blackman-harris"
  "glass|$scenes/glass_showcase.gltf|${size[*]} $glass_args"
)
write_plan "$scratch/plan.json" "$scratch/out" "${jobs[@]}"

start=$(date +%s)
python3 "$farm/kiln_farm.py" submit --plan "$scratch/plan.json" --kiln "$kiln" --work-dir "$scratch/work" \
  --tiles 3 --cpus-per-task 1 --mem 256M --time 5:00 --max-retries 0 --array-limit 2 --wait ||
  fail "the farm run did not complete: $(cat "$scratch"/work/logs/finalize.*.log 2>/dev/null)"
echo "farm: 3 jobs x 3 bands rendered, stitched and verified in $(($(date +%s) - start)) s"
python3 - "$scratch/work/submission.json" <<'PY' || fail "9 tasks on MaxArraySize 5 are not two arrays"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["max_array_size"] == 5 and s["tasks"] == 9 and len(s["render_jobs"]) == 2, s
PY

# compare_to_reference NAME OUTPUT PLAN: a single-process render of PLAN's job NAME must have
# OUTPUT's channels (names and formats), windows and pixels.
compare_to_reference() {
  local name=$1 output=$2 plan=$3 reference="$scratch/reference/$1.exr" command channels
  mkdir -p "$scratch/reference"
  mapfile -t command < <(python3 - "$plan" "$name" <<'PY'
import json, sys
job = next(j for j in json.load(open(sys.argv[1]))["jobs"] if j["name"] == sys.argv[2])
print("\n".join([job["asset"]] + job["render_args"]))
PY
  )
  "$kiln" render "${command[0]}" -o "$reference" "${command[@]:1}" -q
  channels=$(python3 - "$farm" "$reference" "$output" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from kiln_farm import read_exr_header
ref, out = read_exr_header(sys.argv[2]), read_exr_header(sys.argv[3])
for key in ("display_window", "data_window", "channels"):
    if ref[key] != out[key]:
        sys.exit(f"{key}: single process {ref[key]}, farm {out[key]}")
if out["data_window"] != out["display_window"]:
    sys.exit(f"data window {out['data_window']} is not the frame {out['display_window']}")
print(len(out["channels"]))
PY
  ) || fail "$name: the headers differ"
  idiff -q -fail 0 -failpercent 0 -warn 0 -a "$reference" "$output" >/dev/null ||
    fail "$name: pixels differ from the single-process render: $(idiff -a "$reference" "$output" | tail -n 4)"
  echo "farm: $name matches the single-process render ($channels channels)"
}
for name in cornell quadrics glass; do
  compare_to_reference "$name" "$scratch/out/$name.exr" "$scratch/plan.json"
done
python3 - "$scratch/work/verify.json" <<'PY' || fail "verify.json does not report three good outputs"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["ok"] and len(r["jobs"]) == 3, r
assert all(j["ok"] and (j["width"], j["height"]) == (96, 64) for j in r["jobs"]), r
PY

# Retries and failure reports: every render's first attempt fails with exit 1 (an I/O failure as
# kiln reports it), and job "lost" names an asset that does not exist (exit 2, not retried).
wrapper="$scratch/flaky_kiln"
cat >"$wrapper" <<EOF
#!/usr/bin/env bash
if [ "\$1" = render ] && [ -e "\$2" ]; then
  marker="$scratch/attempts/\$(basename "\$4")"
  mkdir -p "$scratch/attempts"
  if [ ! -e "\$marker" ]; then touch "\$marker"; echo "flaky kiln: first attempt fails" >&2; exit 1; fi
fi
exec "$kiln" "\$@"
EOF
chmod +x "$wrapper"
write_plan "$scratch/plan2.json" "$scratch/out2" \
  "cornell|$scenes/cornell_box.gltf|${size[*]} --spp 1" \
  "lost|$scratch/no_such_asset.gltf|${size[*]}"
rc=0
python3 "$farm/kiln_farm.py" submit --plan "$scratch/plan2.json" --kiln "$wrapper" --work-dir "$scratch/work2" \
  --tiles 2 --mem 256M --time 5:00 --max-retries 1 --wait || rc=$?
[ "$rc" -eq 1 ] || fail "a batch with a missing asset must end with exit 1, got $rc"
compare_to_reference cornell "$scratch/out2/cornell.exr" "$scratch/plan2.json"
python3 - "$scratch/work2" <<'PY' || fail "verify.json does not report the lost job as it should"
import glob, json, sys
w = sys.argv[1]
r = json.load(open(f"{w}/verify.json"))
jobs = {j["name"]: j for j in r["jobs"]}
assert not r["ok"], r
assert jobs["cornell"]["ok"], jobs["cornell"]
lost = jobs["lost"]
assert not lost["ok"] and len(lost["problems"]) == 2, lost
for i, p in enumerate(lost["problems"]):
    assert p.startswith(f"band {i} of 2 missing (task {2 + i}: exit 2;"), p
# The good job's bands each failed once and succeeded on the retry; the lost job's were tried once.
for task, attempts in ((0, 2), (1, 2), (2, 1), (3, 1)):
    log = open(glob.glob(f"{w}/logs/render.*_{task}.log")[0]).read()
    assert log.count(f"kiln farm: task {task} attempt") == attempts, (task, log)
PY
echo "farm: a failing first attempt is retried; a missing asset is reported in verify.json and fails the batch"

# Many small jobs: 40 tiny renders and, in the middle of a task, one missing asset, packed 3 a task:
# 41 units in 14 tasks, split into 3 arrays (5 + 5 + 4) by the MaxArraySize scontrol reports.
small=()
for i in $(seq 0 40); do
  asset="$scenes/cornell_box.gltf"
  [ "$i" -eq 19 ] && asset="$scratch/no_such_small.gltf"
  small+=("small$i|$asset|--width 16 --height 12 --spp 1")
done
write_plan "$scratch/plan5.json" "$scratch/out5" "${small[@]}"
start=$(date +%s)
rc=0
python3 "$farm/kiln_farm.py" submit --plan "$scratch/plan5.json" --kiln "$kiln" --work-dir "$scratch/work5" \
  --jobs-per-task 3 --mem 256M --time 5:00 --max-retries 0 --wait || rc=$?
[ "$rc" -eq 1 ] || fail "a packed batch with a missing asset must end with exit 1, got $rc"
python3 - "$scratch/work5" <<'PY' || fail "the packed batch is not reported as it should"
import json, os, re, subprocess, sys
w = sys.argv[1]
s = json.load(open(f"{w}/submission.json"))
assert (s["units"], s["tasks"], s["max_array_size"], len(s["render_jobs"])) == (41, 14, 5, 3), s
r = json.load(open(f"{w}/verify.json"))
good = [j for j in r["jobs"] if j["ok"]]
assert len(good) == 40 and all((j["width"], j["height"]) == (16, 12) for j in good), r
lost = [j for j in r["jobs"] if not j["ok"]]
assert [j["name"] for j in lost] == ["small19"], lost
# Unit 19 is the second of task 6 (units 18-20): array 1, index 1. Its neighbours rendered.
log = f"{w}/logs/render.{s['render_jobs'][1]}_1.log"
assert lost[0]["problems"] == [f"band 0 of 1 missing (task 6: exit 2; log {log})"], lost
text = open(log).read()
for unit in (18, 19, 20):
    assert f"kiln farm: task 6 attempt 0 (unit {unit})" in text, text
# The task with the failed job exits non-zero; the others succeed.
for array, index, code in ((1, 1, "2:0"), (1, 0, "0:0"), (2, 3, "0:0")):
    out = subprocess.run(["scontrol", "show", "job", "-o", f"{s['render_jobs'][array]}_{index}"],
                         capture_output=True, text=True).stdout
    assert re.search(rf"\bExitCode={code}\b", out), (array, index, out)
PY
echo "farm: 41 small jobs packed into 14 tasks in 3 arrays, 40 verified, the lost one reported in $(($(date +%s) - start)) s"

# Names and paths that reach the generated scripts (issue 43, item 7): the work folder, the asset's
# folder, the output's, the kiln binary's path and the job name hold spaces, quotes, $(...),
# backticks, # and %. sbatch takes both scripts, the jobs carry the name exactly, the logs land in
# the work folder (its % taken literally, not as a file name pattern), the output is verified, and
# none of the embedded commands runs: each would create "pwned" in the jobs' working folder.
hostile="a b 'q\" \$(touch pwned) \`touch pwned\` #x %j ;"
odd="$scratch/odd $hostile"
mkdir -p "$odd/assets" "$scratch/jobs cwd"
cp "$scenes/cornell_box.gltf" "$scenes/cornell_box.bin" "$scenes/checker.png" "$odd/assets/"
ln -s "$kiln" "$odd/kiln $hostile"
write_plan "$scratch/plan6.json" "$odd/out $hostile" "job $hostile|$odd/assets/cornell_box.gltf|${size[*]} --spp 1"
(cd "$scratch/jobs cwd" && python3 "$farm/kiln_farm.py" submit --plan "$scratch/plan6.json" --kiln "$odd/kiln $hostile" \
  --work-dir "$odd/work $hostile" --job-name "farm $hostile" --partition test --tiles 2 --mem 256M --time 5:00 \
  --wait) || fail "the run with odd paths and names did not complete: $(cat "$odd/work $hostile"/logs/*.log)"
python3 - "$odd/work $hostile" "farm $hostile" <<'PY2' || fail "the run with odd paths and names is not as it should be"
import json, os, re, subprocess, sys
w, name = sys.argv[1], sys.argv[2]
r = json.load(open(f"{w}/verify.json"))
assert r["ok"] and len(r["jobs"]) == 1 and (r["jobs"][0]["width"], r["jobs"][0]["height"]) == (96, 64), r
s = json.load(open(f"{w}/submission.json"))
for job, suffix, logs in ((s["render_jobs"][0], "render", [f"render.{s['render_jobs'][0]}_{i}.log" for i in (0, 1)]),
                          (s["finalize_job"], "stitch", [f"finalize.{s['finalize_job']}.log"])):
    out = subprocess.run(["scontrol", "show", "job", "-o", job], capture_output=True, text=True).stdout
    m = re.search(r"\bJobName=(.*?) UserId=", out)
    assert m and m.group(1) == f"{name}-{suffix}", out
    for log in logs:
        assert os.path.isfile(os.path.join(w, "logs", log)), (log, os.listdir(os.path.join(w, "logs")))
PY2
compare_to_reference "job $hostile" "$odd/out $hostile/job $hostile.exr" "$scratch/plan6.json"
[ -z "$(find "$scratch" -name 'pwned*')" ] || fail "a command embedded in a name or path ran: $(find "$scratch" -name 'pwned*')"
echo "farm: spaces, quotes, \$(...), backticks, # and % in the work folder, paths and job name reach Slurm intact"

# kiln batch --plan-only resolves a manifest into the same plan format: run it when available.
if "$kiln" batch --help 2>&1 | grep -q -- --plan-only; then
  # Every name kiln batch accepts goes through: spaces and quotes in the asset's file name and
  # folder, an output in a subfolder with spaces and non-ASCII letters, an --out-dir with a space.
  assets="$scratch/assets dir"
  mkdir -p "$assets"
  cp "$scenes/cornell_box.gltf" "$assets/my shot 'v2'.gltf"
  cp "$scenes/cornell_box.bin" "$scenes/checker.png" "$assets/"
  printf 'asset,output\n%s,\n%s,\n%s,%s\n' "$scenes/cornell_box.gltf" "$assets/my shot 'v2'.gltf" \
    "$assets/my shot 'v2'.gltf" "sub dir/ünï cødé.exr" >"$scratch/manifest.csv"
  python3 "$farm/kiln_farm.py" submit --manifest "$scratch/manifest.csv" --out-dir "$scratch/out 3" \
    --kiln "$kiln" --work-dir "$scratch/work3" --tiles 2 --mem 256M --time 5:00 --wait \
    -- "${size[@]}" --spp 1 || fail "the --manifest farm run did not complete: $(cat "$scratch"/work3/logs/*.log)"
  python3 - "$scratch/work3/verify.json" "$scratch/out 3" <<'PY' || fail "the --manifest run's verify.json is not ok"
import json, os, sys
r = json.load(open(sys.argv[1], encoding="utf-8"))
assert r["ok"], r
names = [j["name"] for j in r["jobs"]]
assert names == ["cornell_box", "my shot 'v2'", "sub dir/ünï cødé"], names
for j in r["jobs"]:
    assert j["ok"] and j["output"] == os.path.join(sys.argv[2], j["name"] + ".exr"), j
    assert os.path.isfile(j["output"]), j
PY
  compare_to_reference "my shot 'v2'" "$scratch/out 3/my shot 'v2'.exr" "$scratch/work3/plan.json"
  echo "farm: --manifest through kiln batch --plan-only verified, names with spaces, quotes and non-ASCII included"
  # A sequence: the manifest job's frames become one job (one unit) per frame, each the
  # pixels of `kiln render --frame N`.
  python3 "$source_dir/bench/sequence/make_sequence_scenes.py" "$scratch/anim" >/dev/null
  printf 'asset,frames,fps,resolution,spp\n%s,1-4,8,48x32,1\n' "$scratch/anim/rigid_boxes.gltf" \
    >"$scratch/shot.csv"
  python3 "$farm/kiln_farm.py" submit --manifest "$scratch/shot.csv" --out-dir "$scratch/out4" \
    --kiln "$kiln" --work-dir "$scratch/work4" --tiles 1 --wait ||
    fail "the frames farm run did not complete: $(cat "$scratch"/work4/logs/*.log)"
  # No --time or --mem: both come from the plan's estimates (tiny frames: the 5-minute floor, and
  # 256 MiB + 1.5 x a peak of a few MiB), and the four frames fit one task.
  grep -qx '#SBATCH --time=00:05:00' "$scratch/work4/render.sbatch" || fail "--time not sized from the estimates"
  grep -qE '^#SBATCH --mem=2[5-9][0-9]M$' "$scratch/work4/render.sbatch" || fail "--mem not sized from the estimates"
  [ "$(wc -l <"$scratch/work4/packs.txt")" -eq 1 ] || fail "four tiny frames are not packed into one task"
  python3 - "$scratch/work4/verify.json" <<'PY' || fail "the frames run's verify.json is not ok"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["ok"], r
assert [j["name"] for j in r["jobs"]] == ["rigid_boxes.%04d" % f for f in range(1, 5)], r["jobs"]
PY
  for frame in 0001 0004; do
    compare_to_reference "rigid_boxes.$frame" "$scratch/out4/rigid_boxes.$frame.exr" "$scratch/work4/plan.json"
  done
  echo "farm: a manifest job with frames is one verified job per frame"
else
  echo "farm: --manifest not exercised: this kiln's batch command has no --plan-only"
fi
echo "PASS"
