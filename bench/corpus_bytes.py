#!/usr/bin/env python3
"""What the exact asset costs: ellicast's stream against Draco and gltfpack on real assets.

Usage: bench/corpus_bytes.py ELLICAST NODE_BIN OUT_DIR PATH... (files, or folders searched for
.gltf/.glb/.ply/.obj), or ... OUT_DIR --render to write the table again from OUT_DIR/bytes.json. NODE_BIN holds gltf-transform and gltfpack (npm); draco_encoder comes from
Debian's draco package. Progress goes to stderr, the table to OUT_DIR/bytes.md, the figures to
OUT_DIR/bytes.json.

Columns, all sizes with every byte a receiver needs (framing, scene, images):
- input: the file and every buffer and image it names;
- Draco: glTF through `gltf-transform draco --encode-speed 0 --decode-speed 0` (Draco at its
  smallest, 14-bit positions, 10-bit normals, 12-bit texture coordinates, the rest of the file as
  it was); a mesh file through `draco_encoder -cl 10 -qp 14 -qn 10 -qt 12`;
- gltfpack -cc: meshopt compression and quantization (glTF only);
- ellicast content: every distinct packet of the stream except the repair packets, once each: what
  a receiver must hold for the exact asset (the carousel's repetitions count against its cycle,
  not here), and its ratio to Draco;
- ellicast file: the recorded stream with its repair packets;
- encode: wall time of `ellicast encode`;
- RMS after 1 and 2 cycles at 50% loss: the stream's carousel through `ellicast simulate --loss 0.5
  --seed 1 --cycles N`, decoded, against the original (`ellicast diff`, % of the diagonal; about
  0.001% means the exact asset came through). A tiny stream's cycle is a few packets: where its SCENE
  packet was lost the objects come back without their node transforms, which shows as a large
  figure (TwoCubes: 19.6% after one cycle of 1.4 KB).
"""
import hashlib
import json
import os
import re
import statistics
import subprocess
import sys
import time

MODELS = ('.gltf', '.glb', '.ply', '.obj')


def inputs_of(paths):
    found = []
    for path in map(os.path.abspath, paths):
        if os.path.isfile(path):
            found.append(path)
            continue
        for root, _, names in os.walk(path):
            found += [os.path.join(root, n) for n in names if n.lower().endswith(MODELS)]
    # The same file reached through two folders (a committed copy of a corpus asset) counts once.
    seen, unique = set(), []
    for path in sorted(set(found), key=lambda p: (os.path.basename(p).lower(), p)):
        with open(path, 'rb') as f:
            digest = hashlib.sha256(f.read()).hexdigest()
        if digest not in seen:
            seen.add(digest)
            unique.append(path)
    return unique


def input_bytes(path):
    """The file and what it names (a .gltf's buffers and images)."""
    total = os.path.getsize(path)
    if path.lower().endswith('.gltf'):
        try:
            with open(path, encoding='utf-8') as f:
                doc = json.load(f)
        except (OSError, ValueError):
            return total
        for key in ('buffers', 'images'):
            for item in doc.get(key, []):
                uri = item.get('uri', '')
                if uri and not uri.startswith('data:'):
                    try:
                        total += os.path.getsize(os.path.join(os.path.dirname(path), uri))
                    except OSError:
                        pass
    return total


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, **kw)


def draco_size(path, out, node_bin):
    if path.lower().endswith(('.gltf', '.glb')):
        r = run([os.path.join(node_bin, 'gltf-transform'), 'draco', path, out + '.draco.glb',
                 '--encode-speed', '0', '--decode-speed', '0'])
        return os.path.getsize(out + '.draco.glb') if r.returncode == 0 else None
    r = run(['draco_encoder', '-i', path, '-o', out + '.drc', '-cl', '10', '-qp', '14', '-qn', '10', '-qt', '12'])
    return os.path.getsize(out + '.drc') if r.returncode == 0 else None


def gltfpack_size(path, out, node_bin):
    if not path.lower().endswith(('.gltf', '.glb')):
        return None
    r = run([os.path.join(node_bin, 'gltfpack'), '-i', path, '-o', out + '.pack.glb', '-cc'])
    return os.path.getsize(out + '.pack.glb') if r.returncode == 0 else None


def measure(ellicast, node_bin, path, out, encode_args=(), draco=True):
    row = {'asset': path, 'in_bytes': input_bytes(path)}
    row['draco'] = draco_size(path, out, node_bin) if draco else None
    row['gltfpack'] = gltfpack_size(path, out, node_bin) if draco else None
    stream = out + '.ellc'
    start = time.monotonic()
    r = run([ellicast, 'encode', '-q', *encode_args, path, '-o', stream])
    row['encode_s'] = round(time.monotonic() - start, 2)
    if r.returncode != 0:
        row['error'] = (r.stderr.strip().splitlines() or ['?'])[-1]
        return row
    info = json.loads(run([ellicast, 'inspect', '--json', stream]).stdout)
    row['content'] = sum(t['bytes'] for t in info['packet_types'] if 'REPAIR' not in t['type'])
    row['file'] = os.path.getsize(stream)
    row['points'] = sum(o.get('point_count', 0) for o in info.get('objects', []))
    for cycles, key in (('1', 'rms_half_loss'), ('2', 'rms_half_loss_2')):
        lossy = out + f'.lossy{cycles}.ellc'
        decoded = out + f'.lossy{cycles}' + ('.glb' if path.lower().endswith(('.gltf', '.glb')) else '.ply')
        if run([ellicast, 'simulate', stream, '-o', lossy, '--loss', '0.5', '--seed', '1', '--cycles', cycles]).returncode == 0 and \
                run([ellicast, 'decode', '-q', lossy, '-o', decoded]).returncode == 0:
            d = run([ellicast, 'diff', path, decoded])
            for line in d.stdout.splitlines():
                if line.startswith('A -> B'):  # max, mean, RMS, each as "value (percent%)"
                    percents = re.findall(r'\(\s*([0-9.eE+-]+)%\)', line)
                    row[key] = float(percents[2]) if len(percents) >= 3 else None
    return row


def kb(v):
    return '-' if v is None else f'{v / 1024:.1f}'


def main():
    if len(sys.argv) < 5:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    ellicast, node_bin, out_dir = sys.argv[1:4]
    if sys.argv[4:] == ['--render']:  # the table again from OUT_DIR/bytes.json
        with open(os.path.join(out_dir, 'bytes.json')) as f:
            render(json.load(f), out_dir)
        return
    assets = inputs_of(sys.argv[4:])
    work = os.path.join(out_dir, 'work')
    os.makedirs(work, exist_ok=True)
    rows = []
    for i, path in enumerate(assets):
        print(f'[{i + 1}/{len(assets)}] {path}', file=sys.stderr, flush=True)
        rows.append(measure(ellicast, node_bin, path, os.path.join(work, f'{i:03d}')))
    with open(os.path.join(out_dir, 'bytes.json'), 'w') as f:
        json.dump(rows, f, indent=1)
    render(rows, out_dir)


def render(rows, out_dir):
    common = os.path.commonpath([os.path.dirname(r['asset']) for r in rows]) if rows else ''
    lines = ['| asset | input KB | Draco KB | gltfpack -cc KB | ellicast content KB | content / Draco | ellicast file KB | '
             'encode s | RMS after 1 / 2 cycles at 50% loss |',
             '|---|---:|---:|---:|---:|---:|---:|---:|---:|']
    ratios = []
    for r in rows:
        name = os.path.relpath(r['asset'], common) if common else r['asset']
        if 'error' in r:
            lines.append(f"| {name} | {kb(r['in_bytes'])} | {kb(r['draco'])} | {kb(r['gltfpack'])} | not encoded: "
                         f"{r['error']} | | | {r['encode_s']} | |")
            continue
        ratio = r['content'] / r['draco'] if r['draco'] else None
        if ratio is not None:
            ratios.append(ratio)
        rms = ' / '.join('-' if r.get(k) is None else f"{r[k]:.3f}%" for k in ('rms_half_loss', 'rms_half_loss_2'))
        lines.append(f"| {name} | {kb(r['in_bytes'])} | {kb(r['draco'])} | {kb(r['gltfpack'])} | {kb(r['content'])} | "
                     f"{'-' if ratio is None else f'{ratio:.2f}x'} | {kb(r['file'])} | {r['encode_s']} | "
                     f"{rms} |")
    if ratios:
        lines.append('')
        lines.append(f'{len(ratios)} assets: content / Draco median {statistics.median(ratios):.2f}x, '
                     f'worst {max(ratios):.2f}x, best {min(ratios):.2f}x; '
                     f'{sum(1 for x in ratios if x <= 1.25)} at or under 1.25x, {sum(1 for x in ratios if x > 2)} over 2x.')
    with open(os.path.join(out_dir, 'bytes.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
