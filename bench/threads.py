"""Two threads against one: one `shadelab` binary's scaling, round by round.

    python3 bench/threads.py BINARY ROUNDS [shadelab bench options...]
    python3 bench/threads.py target/release/shadelab 7 --size 1920x1080 --model bunny,dragon,quad

Each round runs `BINARY bench --json --rasterizer tiled --threads 1,2
--frames 101` with the models read from ../shared/models (or
$SHADELAB_MODELS), so a row's one- and two-thread medians are timed back to
back and a slow spell of the machine weighs on both. Prints the cache line's
round trip between the two cores that each round measured as it started
(where the host ran them: about 50-70 ns beside each other, 300 ns and more
apart), then per row the medians over the rounds, their ratio, and the
median, least and greatest of the rounds' own ratios.
"""
import statistics, sys

from common import bench_json
binary, rounds = sys.argv[1], int(sys.argv[2])
extra = sys.argv[3:]
times, trips = {}, []
for r in range(rounds):
    data = bench_json(binary, ['--rasterizer', 'tiled', '--threads', '1,2', '--frames', '101'] + extra)
    trips.append(data['machine']['round_trip_ns'])
    for row in data['rows']:
        key = (row['model'], f"{row['width']}x{row['height']}", row['shading'])
        times.setdefault(key, {}).setdefault(row['threads'], []).append(row['median_ms'])
    print(f'round {r}: round trip {trips[-1]} ns', file=sys.stderr, flush=True)
print('the rounds\' round trips, ns:', ' '.join(map(str, trips)))
print()
print('| model | size | shading | 1 thread ms | 2 threads ms | 2 threads / 1 | rounds\' ratios, median | least | greatest |')
print('|---|---|---|---:|---:|---:|---:|---:|---:|')
for key, by_threads in times.items():
    one, two = by_threads[1], by_threads[2]
    ratios = [a / b for a, b in zip(one, two)]
    a, b = statistics.median(one), statistics.median(two)
    print(f'| {key[0]} | {key[1]} | {key[2]} | {a:.3f} | {b:.3f} | {a / b:.2f}× '
          f'| {statistics.median(ratios):.2f}× | {min(ratios):.2f}× | {max(ratios):.2f}× |')
