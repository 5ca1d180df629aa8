"""Times two `shadelab` binaries side by side on the standard rows.

    python3 bench/ab.py BEFORE AFTER ROUNDS [shadelab bench options...]

Each round runs `BEFORE bench --json` and `AFTER bench --json` (the order
alternating from round to round, so that the machine's load falls on both
alike) with the models read from ../shared/models (or $SHADELAB_MODELS);
then prints each row's median over the rounds, before and after, their
ratio, the median of the rounds' own ratios (a round times BEFORE and
AFTER back to back, so a slow spell of the machine weighs on both), the
same for the least frame of all rounds, in how many rounds AFTER's median
was the lower, and the geometric means of the ratios. On a
machine whose speed changes in phases of seconds (BENCHMARKS.md, "The same
code on an AMD EPYC"), a change the medians and the minima disagree on is
not measured. The raw times, with each frame's, go to /tmp/ab.json.
"""
import json, sys, statistics, math

from common import bench_json
A, B, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
extra = sys.argv[4:]
medians = {A: {}, B: {}}
minima = {A: {}, B: {}}
frames = {A: {}, B: {}}
machine = None
for r in range(rounds):
    for binary in ([A, B] if r % 2 == 0 else [B, A]):
        data = bench_json(binary, extra)
        machine = data.get('machine', machine)
        for row in data['rows']:
            key = (row['model'], f"{row['width']}x{row['height']}", row['shading'], row['rasterizer'], row['threads'])
            medians[binary].setdefault(key, []).append(row['median_ms'])
            minima[binary].setdefault(key, []).append(row['min_ms'])
            frames[binary].setdefault(key, []).append(row.get('frame_ms', []))
        print(f'round {r} {binary} done', file=sys.stderr, flush=True)
json.dump({'machine': machine,
           'a': {str(k): v for k, v in medians[A].items()}, 'b': {str(k): v for k, v in medians[B].items()},
           'a_min': {str(k): v for k, v in minima[A].items()}, 'b_min': {str(k): v for k, v in minima[B].items()},
           'a_frames': {str(k): v for k, v in frames[A].items()}, 'b_frames': {str(k): v for k, v in frames[B].items()}},
          open('/tmp/ab.json', 'w'))
by_median, by_round, by_min = [], [], []
print('| model | size | method | rasterizer | threads | before ms | after ms | after/before | rounds\' after/before, median '
      '| before min | after min | after/before, min | after lower |')
print('|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|')
for key in sorted(medians[A]):
    a, b = statistics.median(medians[A][key]), statistics.median(medians[B][key])
    rounds_ratio = statistics.median(y / x for x, y in zip(medians[A][key], medians[B][key]))
    a_min, b_min = min(minima[A][key]), min(minima[B][key])
    lower = sum(y < x for x, y in zip(medians[A][key], medians[B][key]))
    by_median.append(b / a)
    by_round.append(rounds_ratio)
    by_min.append(b_min / a_min)
    print(f'| {key[0]} | {key[1]} | {key[2]} | {key[3]} | {key[4]} | {a:.3f} | {b:.3f} | {b/a:.3f} | {rounds_ratio:.3f} '
          f'| {a_min:.3f} | {b_min:.3f} | {b_min/a_min:.3f} | {lower} of {len(medians[A][key])} |')
geomean = lambda r: math.exp(sum(map(math.log, r)) / len(r))
print(f'\ngeometric mean after/before: {geomean(by_median):.3f} over {len(by_median)} rows '
      f'(worst {max(by_median):.3f}, best {min(by_median):.3f}); '
      f'of the rounds\' ratios: {geomean(by_round):.3f} (worst {max(by_round):.3f}, best {min(by_round):.3f}); '
      f'of the minima: {geomean(by_min):.3f} (worst {max(by_min):.3f}, best {min(by_min):.3f})')
