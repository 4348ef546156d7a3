#!/usr/bin/env python3
"""How long a receiver waits, at a given loss, for every point of a stream against the whole stream
(what `ellicast validate` calls conforming: every texture byte, animation and morph key, skin joint,
joint weight and displacement record too): the points have repair packets (spec 17), the scene
packets and per-point scene data do not, so the carousel's repetition alone completes them.

For each seed, `ellicast simulate` (tune-in at slot 0, independent loss) and `ellicast validate` are
run on ever longer listening times, bisected to 0.05 cycles, for the first time each part is complete
(the channel's draws for a slot do not depend on how long the receiver listens, so more cycles only
add packets).

Usage: python3 bench/scene_wait.py ELLICAST STREAM.ellc [SEEDS]
  e.g. after `ellicast encode MorphDuck.gltf -o duck.ellc` (MorphDuck.gltf: made by
  tests/test_morph_assets.cpp in the build's test-scratch/morph_duck/)."""
import os
import statistics
import subprocess
import sys
import tempfile


def main():
    ellicast, stream = sys.argv[1:3]
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 12
    received = os.path.join(tempfile.mkdtemp(), 'received.ellc')

    def complete(seed, cycles, loss):
        subprocess.run([ellicast, 'simulate', stream, '-o', received, '--loss', str(loss), '--cycles', str(cycles),
                        '--seed', str(seed)], capture_output=True, check=True)
        out = subprocess.run([ellicast, 'validate', received], capture_output=True, text=True).stdout
        points = 'points received' not in out
        return points, 'conforms to' in out

    def first(seed, loss, part):
        lo, hi = 0.0, 12.0
        if not complete(seed, hi, loss)[part]:
            return float('inf')
        while hi - lo > 0.05:
            mid = (lo + hi) / 2
            if complete(seed, mid, loss)[part]:
                hi = mid
            else:
                lo = mid
        return hi

    print(f'{stream}: cycles after tune-in until complete, {seeds} seeds (median, max)')
    for loss in (0.1, 0.3, 0.5):
        points = [first(s, loss, 0) for s in range(1, seeds + 1)]
        scene = [first(s, loss, 1) for s in range(1, seeds + 1)]
        print(f'  loss {loss:.0%}: every point {statistics.median(points):.2f}, {max(points):.2f}; '
              f'the whole stream {statistics.median(scene):.2f}, {max(scene):.2f}',
              flush=True)
        print(f'[{loss:.0%} done]', file=sys.stderr, flush=True)


if __name__ == '__main__':
    main()
