"""Two `shadelab` binaries side by side, each pair labelled by where the
host ran the two cores.

    python3 bench/ab_placed.py BEFORE AFTER SECONDS MODEL:SHADING... [--size WxH] [--out FILE]
    python3 bench/ab_placed.py main-build try-build 720 bunny:flat dragon:gouraud

For SECONDS, the rows take turns; each pair runs `BEFORE bench --json` and
`AFTER bench --json` on one row (2 threads, tiled, 101 frames; the order
alternating) with the models from ../shared/models (or $SHADELAB_MODELS).
Each call measures a cache line's round trip between the two cores as it
starts (`machine.round_trip_ns`): a pair whose two readings are both above
250 ns is "apart", both below 150 ns "beside", else "mixed" (the host moved
the cores between the calls). On a virtual machine whose host moves the
cores every few seconds to hours (BENCHMARKS.md, "Where the two threads'
cores are"), a change that matters only in one state is measured only this
way. Prints per row and state the pairs, both medians, the median of the
pairs' ratios after/before and in how many pairs AFTER was faster; the raw
pairs go to FILE (default /tmp/ab_placed.jsonl), one JSON object a line.
"""
import argparse, json, statistics, time

from common import bench_json

parser = argparse.ArgumentParser()
parser.add_argument('before')
parser.add_argument('after')
parser.add_argument('seconds', type=float)
parser.add_argument('rows', nargs='+', help='MODEL:SHADING, e.g. bunny:flat')
parser.add_argument('--size', default='1920x1080')
parser.add_argument('--out', default='/tmp/ab_placed.jsonl')
args = parser.parse_args()


def call(binary, model, shading):
    """One `bench --json` call: its round trip (ns) and its median (ms)."""
    data = bench_json(binary, ['--rasterizer', 'tiled', '--frames', '101', '--threads', '2',
                               '--size', args.size, '--model', model, '--shading', shading])
    return data['machine']['round_trip_ns'], data['rows'][0]['median_ms']


def state(trips):
    if all(t > 250 for t in trips):
        return 'apart'
    if all(t < 150 for t in trips):
        return 'beside'
    return 'mixed'


pairs = []
end, k = time.time() + args.seconds, 0
with open(args.out, 'w') as raw:
    while time.time() < end:
        model, shading = args.rows[k % len(args.rows)].split(':')
        first, second = (args.before, args.after) if k % 2 == 0 else (args.after, args.before)
        got = {first: call(first, model, shading), second: call(second, model, shading)}
        pair = {'model': model, 'shading': shading, 'before': got[args.before], 'after': got[args.after]}
        raw.write(json.dumps(pair) + '\n')
        raw.flush()
        pairs.append(pair)
        k += 1

groups = {}
for p in pairs:
    key = (p['model'], p['shading'], state([p['before'][0], p['after'][0]]))
    groups.setdefault(key, []).append((p['before'][1], p['after'][1]))
print(f'{len(pairs)} pairs in {args.seconds:.0f} s, 2 threads, {args.size}')
print()
print('| row | cores | pairs | before ms | after ms | after / before, median of the pairs | after faster |')
print('|---|---|---:|---:|---:|---:|---:|')
for (model, shading, where), times in sorted(groups.items()):
    before = [b for b, _ in times]
    after = [a for _, a in times]
    ratios = [a / b for b, a in times]
    faster = sum(a < b for b, a in times)
    print(f'| {model} {shading} | {where} | {len(times)} | {statistics.median(before):.3f} '
          f'| {statistics.median(after):.3f} | {statistics.median(ratios):.3f} | {faster} |')
