"""Times two `shadelab` binaries side by side on the standard rows.

    python3 bench/ab.py BEFORE AFTER ROUNDS [shadelab bench options...]

Each round runs `BEFORE bench --json` and `AFTER bench --json` (the order
alternating from round to round, so that the machine's load falls on both
alike) with the models read from ../shared/models (or $SHADELAB_MODELS);
then prints each row's median over the rounds, before and after, their
ratio, and the geometric mean of the ratios. The raw times go to
/tmp/ab.json.
"""
import json, os, subprocess, sys, statistics, math

MODELS = os.environ.get('SHADELAB_MODELS') or os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'shared', 'models')
A, B, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
extra = sys.argv[4:]
res = {A: {}, B: {}}
machine = None
for r in range(rounds):
    for binary in ([A, B] if r % 2 == 0 else [B, A]):
        out = subprocess.run([binary, 'bench', '--json', '--models-dir', MODELS] + extra, capture_output=True, text=True, check=True).stdout
        data = json.loads(out)
        machine = data.get('machine', machine)
        for row in data['rows'] if 'rows' in data else data['records']:
            key = (row['model'], row['size'] if 'size' in row else f"{row['width']}x{row['height']}", row['shading'], row['rasterizer'], row['threads'])
            res[binary].setdefault(key, []).append(row['median_ms'] if 'median_ms' in row else row['ms_median'])
        print(f'round {r} {binary} done', file=sys.stderr, flush=True)
json.dump({'machine': machine, 'a': {str(k): v for k, v in res[A].items()}, 'b': {str(k): v for k, v in res[B].items()}}, open('/tmp/ab.json', 'w'))
ratios = []
print('| model | size | method | rasterizer | threads | before ms | after ms | after/before |')
print('|---|---|---|---|---:|---:|---:|---:|')
for key in sorted(res[A]):
    a = statistics.median(res[A][key]); b = statistics.median(res[B][key])
    ratios.append(b / a)
    print(f'| {key[0]} | {key[1]} | {key[2]} | {key[3]} | {key[4]} | {a:.3f} | {b:.3f} | {b/a:.3f} |')
g = math.exp(sum(map(math.log, ratios)) / len(ratios))
print(f'\ngeometric mean after/before: {g:.3f} over {len(ratios)} rows; worst {max(ratios):.3f}; best {min(ratios):.3f}')
