#!/usr/bin/env python3
"""Speed side by side with Draco (issue 30), in one run on this machine.

Usage: bench/speed.py ELLICAST SAMPLES_MESHES OUT_TXT [--large] [--runs N] [--gltf A.glb,B.gltf,...]
                      [--baseline OTHER_ELLICAST] [--instructions]

Models: the bunny (shared samples), the bumpy torus of bench_encode (400 x 125 = 50,000 vertices,
closed, written here as a binary PLY) and, with --large, the same torus sampled ten times finer
(1000 x 500 = 500,000 vertices: the parametric surface evaluated at the midpoints, which is what a
subdivision onto the surface gives). For each, the best wall time of N runs (default 3) of:
- encode: `ellicast encode` with its defaults (--threads 2) against `draco_encoder -cl 7 -qp 14`
  (14-bit positions, as ellicast's default);
- exact decode: `ellicast decode` of every packet (the exact layer: the original triangles) against
  `draco_decoder`, both to a PLY;
- reconstruction: `ellicast decode --no-exact` of every packet (ellipsoids, marching cubes, every point
  inserted with flips and collapses): its wall time, and the insertion stage alone as the decoder
  reports it, in points per second.
Ratios are ellicast / Draco (a reconstruction against Draco's decode of the same model). With --gltf,
low-poly glTF assets too (encode, exact decode, reconstruction; draco_encoder reads no glTF). With
--baseline, the same steps with another build of ellicast (an earlier commit), in the same run, and
whether its streams and reconstructions are byte for byte the same. Speed figures mean something
only on an otherwise idle machine: the table records the load average. With --instructions, the
exact decode and the reconstruction of each mesh model are also counted in instructions under
valgrind's callgrind (deterministic, where this machine's wall times wander by 20-50% between runs),
and so is the encode with one thread of the models up to 50k vertices and the glTF assets, for the
baseline too: a change of a few percent shows there and nowhere else.
"""
import math
import os
import re
import struct
import subprocess
import sys
import tempfile
import time


def bumpy_torus(u, v, path):
    """bench_encode.cpp's bumpy_torus(u, v) as a binary little-endian PLY."""
    positions = []
    for i in range(u):
        for j in range(v):
            a, b = 2 * math.pi * i / u, 2 * math.pi * j / v
            r = 0.35 + 0.06 * math.sin(5 * a) * math.cos(3 * b) + 0.03 * math.sin(11 * b)
            R = 1.0 + 0.15 * math.cos(3 * a)
            positions.append(((R + r * math.cos(b)) * math.cos(a), (R + r * math.cos(b)) * math.sin(a),
                              r * math.sin(b) + 0.2 * math.sin(2 * a)))
    faces = []
    for i in range(u):
        for j in range(v):
            p, q = i * v + j, ((i + 1) % u) * v + j
            r, s = ((i + 1) % u) * v + (j + 1) % v, i * v + (j + 1) % v
            faces.append((p, q, r))
            faces.append((p, r, s))
    with open(path, 'wb') as f:
        f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
                 'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'
                 % (len(positions), len(faces))).encode())
        f.write(b''.join(struct.pack('<fff', *p) for p in positions))
        f.write(b''.join(struct.pack('<Biii', 3, *t) for t in faces))


def timed(cmd):
    t0 = time.perf_counter()
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    elapsed = time.perf_counter() - t0
    if out.returncode != 0:
        sys.exit('speed: %s failed:\n%s' % (' '.join(cmd), out.stdout))
    return elapsed, out.stdout


def best(runs, cmd):
    results = [timed(cmd) for _ in range(runs)]
    return min(r[0] for r in results), min(results)[1]


def option(args, name, default=None):
    """Removes `name VALUE` from args and returns VALUE (or default)."""
    if name not in args:
        return default
    k = args.index(name)
    value = args[k + 1]
    del args[k:k + 2]
    return value


def reconstruction(ellicast, stream, out, runs):
    """Best wall time of `decode --no-exact` and the best insertion stage it reports; its log."""
    rec, insertion, log = float('inf'), float('inf'), ''
    for _ in range(runs):
        elapsed, log = timed([ellicast, 'decode', '-q', '--no-exact', stream, '-o', out])
        rec = min(rec, elapsed)
        insertion = min([insertion] + [float(x) for x in re.findall(r'insertion ([\d.]+) s', log)])
    return rec, insertion, log


def instructions(cmd):
    """Instructions `cmd` executes (valgrind --tool=callgrind), or None without valgrind."""
    try:
        out = subprocess.run(['valgrind', '--tool=callgrind', '--callgrind-out-file=/dev/null'] + cmd,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    except FileNotFoundError:
        return None
    m = re.search(r'Collected : (\d+)', out.stderr) or re.search(r'I\s+refs:\s+([\d,]+)', out.stderr)
    if out.returncode != 0 or not m:
        sys.exit('speed: %s failed under valgrind:\n%s' % (' '.join(cmd), out.stderr[-2000:]))
    return int(m.group(1).replace(',', ''))


def same_bytes(a, b):
    with open(a, 'rb') as fa, open(b, 'rb') as fb:
        return fa.read() == fb.read()


def with_baseline(baseline, path, stem, ext, runs):
    """The same steps with the baseline build: its encode, exact decode, reconstruction and insertion
    times, and whether its stream and reconstruction are the same bytes as this build's."""
    enc, _ = best(runs, [baseline, 'encode', '-q', path, '-o', stem + '.before.ellc'])
    dec, _ = best(runs, [baseline, 'decode', '-q', stem + '.before.ellc', '-o', stem + '.before.exact' + ext])
    rec, insertion, _ = reconstruction(baseline, stem + '.before.ellc', stem + '.before.rec' + ext, runs)
    return (enc, dec, rec, insertion, same_bytes(stem + '.ellc', stem + '.before.ellc'),
            same_bytes(stem + '.rec' + ext, stem + '.before.rec' + ext))


def main():
    args = sys.argv[1:]
    large = '--large' in args
    count = '--instructions' in args
    args = [a for a in args if a not in ('--large', '--instructions')]
    runs = int(option(args, '--runs', 3))
    baseline = option(args, '--baseline')
    gltf = option(args, '--gltf')
    ellicast, meshes, out_txt = args[:3]
    tmp = tempfile.mkdtemp(prefix='ellicast-speed-')
    models = [('bunny', os.path.join(meshes, 'bunny.ply'))]
    torus = os.path.join(tmp, 'torus50k.ply')
    bumpy_torus(400, 125, torus)
    models.append(('torus 50k (closed)', torus))
    if large:
        big = os.path.join(tmp, 'torus500k.ply')
        bumpy_torus(1000, 500, big)
        models.append(('torus 500k (closed)', big))
    lines = []

    def say(line=''):
        print(line, flush=True)
        lines.append(line)

    say('Speed: ellicast against Draco (draco_encoder -cl 7 -qp 14 / draco_decoder), best wall time of %d runs,'
        % runs)
    say('load average at the start: %s' % ' '.join('%.2f' % x for x in os.getloadavg()))
    if baseline:
        say('baseline: %s, run in the same session on the same inputs (its streams compared byte for byte)'
            % baseline)
    say()
    say('| model | vertices | points | encode ellicast | encode Draco | ratio | exact decode ellicast | decode Draco '
        '| ratio | reconstruction (wall) | ratio | insertion | points/s |')
    say('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|')
    before = []
    for name, path in models:
        stem = os.path.join(tmp, re.sub(r'\W+', '_', name))
        enc, _ = best(runs, [ellicast, 'encode', '-q', path, '-o', stem + '.ellc'])
        denc, _ = best(runs, ['draco_encoder', '-i', path, '-o', stem + '.drc', '-cl', '7', '-qp', '14'])
        dec, _ = best(runs, [ellicast, 'decode', '-q', stem + '.ellc', '-o', stem + '.exact.ply'])
        ddec, _ = best(runs, ['draco_decoder', '-i', stem + '.drc', '-o', stem + '.draco.ply'])
        rec, insertion, log = reconstruction(ellicast, stem + '.ellc', stem + '.rec.ply', runs)
        points = sum(int(a) for a, _ in re.findall(r'(\d+)/(\d+) points', log))
        with open(path, 'rb') as f:
            head = f.read(4096).decode('latin-1')
        vertices = re.search(r'element vertex (\d+)', head)
        say('| %s | %s | %d | %.2f s | %.3f s | %.0fx | %.3f s | %.3f s | %.1fx | %.2f s | %.0fx | %.2f s | %.0f |' % (
            name, vertices.group(1) if vertices else '?', points, enc, denc, enc / denc, dec, ddec, dec / ddec, rec,
            rec / ddec, insertion, points / insertion if insertion > 0 else float('nan')))
        if baseline:
            before.append((name, enc, dec, rec, insertion) + with_baseline(baseline, path, stem, '.ply', runs))
    # Low-poly glTF assets: what a catalogue holds (encode and reconstruction only: draco_encoder
    # reads no glTF).
    if gltf:
        say()
        say('| low-poly glTF | encode ellicast | exact decode | reconstruction (wall) |')
        say('|---|---:|---:|---:|')
        for path in gltf.split(','):
            name = os.path.basename(path)
            stem = os.path.join(tmp, re.sub(r'\W+', '_', name))
            enc, _ = best(runs, [ellicast, 'encode', '-q', path, '-o', stem + '.ellc'])
            dec, _ = best(runs, [ellicast, 'decode', '-q', stem + '.ellc', '-o', stem + '.exact.glb'])
            rec, _, _ = reconstruction(ellicast, stem + '.ellc', stem + '.rec.glb', runs)
            say('| %s | %.2f s | %.3f s | %.2f s |' % (name, enc, dec, rec))
            if baseline:
                before.append((name, enc, dec, rec, float('nan')) + with_baseline(baseline, path, stem, '.glb', runs))
    say()
    say('reconstruction = `ellicast decode --no-exact` of every packet, whole process; insertion = its insertion '
        'stage (points with their flips and collapses) as the decoder reports it.')
    if before:
        say()
        say('Against the baseline build (before / now, wall):')
        say()
        say('| model | encode | exact decode | reconstruction | insertion | same stream | same reconstruction |')
        say('|---|---:|---:|---:|---:|---|---|')
        for name, enc, dec, rec, ins, benc, bdec, brec, bins, same, same_rec in before:
            insertion = '%.2f / %.2f s' % (bins, ins) if ins == ins else '-'
            say('| %s | %.2f / %.2f s (%.2fx) | %.3f / %.3f s (%.2fx) | %.2f / %.2f s | %s | %s | %s |' % (
                name, benc, enc, enc / benc, bdec, dec, dec / bdec, brec, rec, insertion,
                'yes' if same else 'NO', 'yes' if same_rec else 'NO'))
    if count:
        say()
        say('Instructions (valgrind --tool=callgrind, one run each; deterministic). The encode runs with one thread '
            '(`--threads 1`; the stream is the same with any number), on the models of at most 50,000 vertices and '
            'the low-poly glTF assets (the 500k torus would take half an hour under valgrind):')
        say()
        say('| model | encode, 1 thread | exact decode | reconstruction |')
        say('|---|---:|---:|---:|')
        rows = [(name, path, '.ply', True) for name, path in models]
        rows += [(os.path.basename(path), path, '.glb', False) for path in (gltf.split(',') if gltf else [])]
        for name, path, ext, mesh in rows:
            print('speed: counting instructions for %s (valgrind: a few minutes)' % name, file=sys.stderr, flush=True)
            stem = os.path.join(tmp, re.sub(r'\W+', '_', name))
            def steps(tool, stream):  # the encode (small models), the exact decode and the reconstruction
                encode = [tool, 'encode', '-q', '--threads', '1', path, '-o', stem + '.count.ellc']
                return [encode if '500k' not in name else None,
                        [tool, 'decode', '-q', stream, '-o', stem + '.count' + ext] if mesh else None,
                        [tool, 'decode', '-q', '--no-exact', stream, '-o', stem + '.count' + ext] if mesh else None]
            now = [instructions(cmd) if cmd else 0 for cmd in steps(ellicast, stem + '.ellc')]
            if None in now:
                say('(valgrind is not installed: no instruction counts)')
                break
            was = [instructions(cmd) if cmd else 0 for cmd in steps(baseline, stem + '.before.ellc')] if baseline else None
            cells = []
            for k, n in enumerate(now):
                if not n:
                    cells.append('-')
                elif was:
                    cells.append('%.1fM / %.1fM (%.2fx)' % (was[k] / 1e6, n / 1e6, n / was[k]))
                else:
                    cells.append('%.1fM' % (n / 1e6))
            say('| %s | %s |' % (name, ' | '.join(cells)))
        if baseline:
            say()
            say('(each cell: baseline / now)')
    with open(out_txt, 'w') as f:
        f.write('\n'.join(lines) + '\n')


if __name__ == '__main__':
    main()
