# A/B runs of `kiln bench` on a loaded machine: bench_ab.py OUTDIR ROUNDS SCENE [view options] -- NAME=KILN[:options] ...
# runs every variant once per round, alternating them so drifting load hits all alike, writes each run's
# JSON and CSV to OUTDIR, and prints per variant the medians over rounds (render wall and CPU seconds,
# rays/s per kind, Embree memory) and the median of the per-round ratios to the first variant.
import json, subprocess, sys, statistics, os, shlex
out, rounds = sys.argv[1], int(sys.argv[2])
rest = sys.argv[3:]; i = rest.index('--'); scene = rest[:i]; variants = [v.split('=',1) for v in rest[i+1:]]
os.makedirs(out, exist_ok=True)
res = {n: [] for n, _ in variants}
for r in range(rounds):
    for n, spec in variants:
        b, _, extra = spec.partition(':')
        j = f"{out}/{n}_{r}.json"
        cmd = [b, 'bench', *scene, '-q', '--repeat', '3', '--json', j, '--csv', j[:-5] + '.csv', '--label', n,
               *shlex.split(extra)]
        for attempt in range(5):  # OIIO's cache assert (decr_tiles) is flaky, before and after this change
            if subprocess.run(cmd).returncode == 0: break
        else: raise SystemExit('failed: ' + ' '.join(cmd))
        res[n].append(json.load(open(j)))
base = None
for n, runs in res.items():
    rs = statistics.median(x['render_seconds'] for x in runs)
    kinds = {}
    for x in runs:
        for k in x['kinds']:
            kinds.setdefault(k['kind']+'/'+k['query'], []).append((k['bare_embree_mrays_per_s'], k['kiln_query_mrays_per_s'], k['kiln_query_over_bare']))
            if 'bare_stream_mrays_per_s' in k: kinds.setdefault(k['kind']+'/stream', []).append((k['bare_stream_mrays_per_s'], k['kiln_stream_mrays_per_s'], k['kiln_stream_over_bare']))
    ratio = statistics.median(x['render_over_bare'] for x in runs)
    if base is None: base, base_runs = rs, runs
    paired = statistics.median(b['render_seconds'] / x['render_seconds'] for b, x in zip(base_runs, runs))
    cpu = [x.get('render_cpu_seconds', 0) for x in runs]
    base_cpu = [b.get('render_cpu_seconds', 0) for b in base_runs]
    cpu_paired = statistics.median(b / c for b, c in zip(base_cpu, cpu)) if all(cpu) and all(base_cpu) else 0
    # Fields the kiln before this change does not write read as 0.
    emb = statistics.median(x.get('embree_bytes', {}).get('after_build', 0) for x in runs) / 1e6
    embp = statistics.median(x.get('embree_bytes', {}).get('peak', 0) for x in runs) / 1e6
    rssd = statistics.median(x.get('build_rss_delta_bytes', 0) for x in runs) / 1e6
    print(f"{n:10s} embree {emb:.2f} MB (peak {embp:.2f}) build RSS delta {rssd:.2f} MB")
    print(f"{n:10s} render {rs:.4f}s (median paired speed-up vs first x{paired:.3f}) cpu {statistics.median(cpu):.4f}s (paired x{cpu_paired:.3f}) render/bare {ratio:.3f} build {statistics.median(x['build_seconds'] for x in runs):.4f}s")
    for k, v in kinds.items():
        print(f"   {k:22s} bare {statistics.median(a for a,_,_ in v):6.2f} kiln {statistics.median(b for _,b,_ in v):6.2f} ratio {statistics.median(c for _,_,c in v):.3f}")
