#!/usr/bin/env python3
"""The point share (format 1.11, spec 27): bytes of the exact asset against Draco, and the picture at 50% loss,
as a smaller share of each object's vertices travels as points and the exact layer carries the others.

Usage: bench/point_share.py ELLICAST NODE_BIN OUT_DIR MODEL... [--shares 1,0.5,0.25,0]
Writes OUT_DIR/point_share.md (the table) and OUT_DIR/point_share.json; progress on stderr.

Per model and share (columns as in bench/corpus_bytes.py, which measures each row):
- ellicast content: every distinct packet but the repair packets, what a receiver holds for the exact asset,
  and its ratio to Draco at its smallest (`draco_encoder -cl 10 -qp 14`, or gltf-transform draco for glTF);
- points: the points the stream sends (the rest of the vertices are carried by the exact layer);
- RMS after 1 and 2 cycles of the carousel at 50% loss (`ellicast simulate --loss 0.5 --seed 1`), decoded,
  against the original, % of the diagonal: about 0.001% means the exact asset came through.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import corpus_bytes  # noqa: E402


def main():
    args = sys.argv[1:]
    shares = [1.0, 0.5, 0.25, 0.0]
    if '--shares' in args:
        i = args.index('--shares')
        shares = [float(v) for v in args[i + 1].split(',')]
        del args[i:i + 2]
    if len(args) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    ellicast, node_bin, out_dir, models = args[0], args[1], args[2], args[3:]
    work = os.path.join(out_dir, 'work')
    os.makedirs(work, exist_ok=True)
    rows = []
    total = len(models) * len(shares)
    for m, path in enumerate(models):
        name = os.path.splitext(os.path.basename(path))[0]
        draco = None
        for s, share in enumerate(shares):
            print(f'[{m * len(shares) + s + 1}/{total}] {name} at point share {share}', file=sys.stderr, flush=True)
            row = corpus_bytes.measure(ellicast, node_bin, os.path.abspath(path), os.path.join(work, f'{name}-{share}'),
                                       ['--point-share', str(share)], draco=draco is None)
            if draco is None:
                draco = row['draco']
            row['draco'] = draco
            row['share'] = share
            rows.append(row)
    with open(os.path.join(out_dir, 'point_share.json'), 'w') as f:
        json.dump(rows, f, indent=1)
    lines = ['| model | point share | points | ellicast content KB | Draco KB | content / Draco | file KB (with repair) | '
             'encode s | RMS after 1 / 2 cycles at 50% loss |', '|---|---:|---:|---:|---:|---:|---:|---:|---:|']
    for r in rows:
        name = os.path.basename(r['asset'])
        if 'error' in r:
            lines.append(f"| {name} | {r['share']} | not encoded: {r['error']} | | | | | | |")
            continue
        ratio = f"{r['content'] / r['draco']:.2f}x" if r['draco'] else '-'
        rms = ' / '.join('-' if r.get(k) is None else f'{r[k]:.3f}%' for k in ('rms_half_loss', 'rms_half_loss_2'))
        lines.append(f"| {name} | {r['share']} | {r.get('points', '-')} | {corpus_bytes.kb(r['content'])} | "
                     f"{corpus_bytes.kb(r['draco'])} | {ratio} | {corpus_bytes.kb(r['file'])} | {r['encode_s']} | {rms} |")
    with open(os.path.join(out_dir, 'point_share.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))
    return 0


if __name__ == '__main__':
    sys.exit(main())
