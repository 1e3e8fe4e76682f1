# Markdown tables from a run folder's JSON (FOLDER/json/<case>/<variant>_<round>.json): medians over
# rounds, and speed-ups as the median of per-round ratios (variants ran alternately, so each round's
# ratio compares runs under the same machine load).
# Usage: bench_tables.py [FOLDER]   (default docs/performance/build-options)
import glob, json, os, re, statistics, sys
here = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(os.path.abspath(__file__)), '..', '..', 'docs', 'performance', 'build-options')
med = statistics.median

def kind(run, name, query):
    return next((k for k in run['kinds'] if k['kind'] == name and k['query'] == query), None)

def cell(values, fmt):
    values = [v for v in values if v is not None]
    return format(med(values), fmt) if values else '–'

for case in sorted(glob.glob(os.path.join(here, 'json', '*'))):
    runs = {}
    for f in glob.glob(os.path.join(case, '*.json')):
        name, r = re.match(r'(.+)_(\d+)\.json$', os.path.basename(f)).groups()
        runs.setdefault(name, {})[int(r)] = json.load(open(f))
    order = sorted(runs, key=lambda n: min(os.path.getmtime(os.path.join(case, f'{n}_{r}.json')) for r in runs[n]))
    first = order[0]
    cpu_ref = next((n for n in order if all('render_cpu_seconds' in x for x in runs[n].values())), None)
    print(f"\n#### {os.path.basename(case)} ({runs[first][0]['scene_file'].split('/')[-1]}, "
          f"{runs[first][0]['width']}x{runs[first][0]['height']}, {runs[first][0]['threads']} threads)\n")
    print('| variant | render s | wall x vs ' + first + ' | CPU x vs ' + str(cpu_ref) +
          ' | render/bare | camera kiln/bare | camera bare stream/bare | camera kiln stream/bare | shadow kiln/bare '
          '| build s | Embree MB (peak) | RSS Δ build MB |')
    print('|---' * 12 + '|')
    for n in order:
        rs = runs[n]
        rounds = sorted(set(rs) & set(runs[first]))
        wall = med(runs[first][r]['render_seconds'] / rs[r]['render_seconds'] for r in rounds)
        cpu = '–'
        if cpu_ref and all('render_cpu_seconds' in x for x in rs.values()):
            cpu = format(med(runs[cpu_ref][r]['render_cpu_seconds'] / rs[r]['render_cpu_seconds'] for r in rounds), '.3f')
        cam = [kind(x, 'camera', 'intersect') for x in rs.values()]
        sh = [kind(x, 'shadow', 'occluded') for x in rs.values()]
        emb = [x.get('embree_bytes') for x in rs.values()]
        print(f"| {n} | {cell([x['render_seconds'] for x in rs.values()], '.3f')} | {wall:.3f} | {cpu} "
              f"| {cell([x['render_over_bare'] for x in rs.values()], '.3f')} "
              f"| {cell([c and c['kiln_query_over_bare'] for c in cam], '.3f')} "
              f"| {cell([c and c.get('bare_stream_over_bare') for c in cam], '.2f')} "
              f"| {cell([c and c.get('kiln_stream_over_bare') for c in cam], '.2f')} "
              f"| {cell([s and s['kiln_query_over_bare'] for s in sh], '.3f')} "
              f"| {cell([x['build_seconds'] for x in rs.values()], '.3f')} "
              f"| {cell([e and e['after_build'] / 1e6 for e in emb], '.2f')} ({cell([e and e['peak'] / 1e6 for e in emb], '.2f')}) "
              f"| {cell([x.get('build_rss_delta_bytes', 0) / 1e6 if 'build_rss_delta_bytes' in x else None for x in rs.values()], '.1f')} |")
