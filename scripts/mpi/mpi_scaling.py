#!/usr/bin/env python3
"""Per-block cost distribution of a sweep and its predicted behaviour on more ranks.

Usage: scripts/mpi/mpi_scaling.py BLOCKS.txt [--groups 1,4,16] [--workers 1,2,4,...]
                              [--cost seconds|steps]

BLOCKS.txt is written by `dpend-mpi sweep --block-times FILE` (columns: block, rank,
initial conditions, RK4 steps, kernel seconds), best from a run on 1 rank x 1 thread
so that the seconds are not disturbed by other workers. For every grouping g (g
consecutive measured blocks make one block, i.e. a block g times larger) and every
number of workers W (MPI ranks x OpenMP threads, all served by the one shared
counter), the dynamic schedule of dpend-mpi is replayed: blocks are handed out in
index order, each to the first worker that is free. Printed: the predicted wall
time, the parallel efficiency total / (W x wall), and the bound of a greedy
schedule, wall <= total / W + max block (the tail: the last block started may be
the largest). Overheads (counter, writes: about 1 ms per block here) are left out.
With --cost steps, a block costs its number of RK4 steps times the mean time per
step of the file: deterministic, free of the noise of a shared machine.
Standard library only.
"""
import heapq
import statistics
import sys


def read_blocks(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith('#') or not line.strip():
                continue
            b, _rank, n, steps, secs = line.split()
            rows.append((int(b), int(n), int(steps), float(secs)))
    rows.sort()
    return rows


def schedule(costs, workers):
    """Replay the shared-counter schedule: returns (wall, busy per worker)."""
    free = [(0.0, w) for w in range(workers)]
    busy = [0.0] * workers
    for c in costs:
        t, w = heapq.heappop(free)
        busy[w] += c
        heapq.heappush(free, (t + c, w))
    return max(t for t, _ in free), busy


def pct(sorted_x, p):
    return sorted_x[min(len(sorted_x) - 1, max(0, int(p * len(sorted_x) + 0.5) - 1))]


def main(argv):
    if len(argv) < 2 or argv[1] in ('-h', '--help'):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    groups = [1]
    cost = 'seconds'
    workers = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512]
    args = argv[2:]
    while args:
        opt = args.pop(0)
        if opt == '--groups':
            groups = [int(x) for x in args.pop(0).split(',')]
        elif opt == '--cost':
            cost = args.pop(0)
            if cost not in ('seconds', 'steps'):
                print('mpi_scaling.py: --cost is seconds or steps', file=sys.stderr)
                return 2
        elif opt == '--workers':
            workers = [int(x) for x in args.pop(0).split(',')]
        else:
            print(f'mpi_scaling.py: unknown option {opt!r}', file=sys.stderr)
            return 2
    rows = read_blocks(argv[1])
    secs = [r[3] for r in rows]
    steps = [r[2] for r in rows]
    total = sum(secs)
    s = sorted(secs)
    print(f'blocks: {len(rows)} of {rows[0][1]} initial conditions; total kernel time '
          f'{total:.2f} s; {sum(steps) / total * 1e-6:.1f} M steps/s '
          f'({total / sum(steps) * 1e9:.1f} ns per trajectory-step)')
    print(f'block seconds: min {s[0]:.4f}  p10 {pct(s, .1):.4f}  p50 {pct(s, .5):.4f}  '
          f'p90 {pct(s, .9):.4f}  p99 {pct(s, .99):.4f}  max {s[-1]:.4f}  '
          f'mean {statistics.fmean(s):.4f}  cv {statistics.pstdev(s) / statistics.fmean(s):.3f}'
          f'  max/mean {s[-1] / statistics.fmean(s):.2f}')
    rate = [st / sc for st, sc in zip(steps, secs) if sc > 0]
    cv_rate = statistics.pstdev(rate) / statistics.fmean(rate)
    print(f'steps per second over the blocks: cv {cv_rate:.3f}'
          ' (the cost of a block is its number of RK4 steps)')
    unit = secs
    if cost == 'steps':
        per_step = total / sum(steps)
        unit = [st * per_step for st in steps]
        print(f'costs from the step counts at {per_step * 1e9:.1f} ns per trajectory-step')
    for g in groups:
        costs = [sum(unit[i:i + g]) for i in range(0, len(unit), g)]
        cmax, cmean = max(costs), statistics.fmean(costs)
        print()
        print(f'block = {g} x {rows[0][1]} initial conditions: {len(costs)} blocks, '
              f'max {cmax:.3f} s, mean {cmean:.3f} s, '
              f'cv {statistics.pstdev(costs) / cmean:.3f}')
        print('| workers | blocks per worker | predicted wall [s] | efficiency | '
              'max/mean busy | greedy bound total/W + max [s] |')
        print('| --- | --- | --- | --- | --- | --- |')
        for w in workers:
            wall, busy = schedule(costs, w)
            mean_busy = total / w
            print(f'| {w} | {len(costs) / w:.1f} | {wall:.3f} | {total / (w * wall) * 100:.1f} % '
                  f'| {max(busy) / mean_busy:.3f} | {total / w + cmax:.3f} |')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
