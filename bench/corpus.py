#!/usr/bin/env python3
"""Real glTF assets through `ellicast convert`: sizes, time, the Khronos validator's verdict, and
what of the scene comes back (nodes, materials, images, animations, skins, morph targets), as a
Markdown table.

Usage: bench/corpus.py ELLICAST NODE_MODULES OUT_DIR FOLDER... (every .gltf / .glb under the folders;
the reference's bench/run.sh corpus passes ../shared/samples/gltf and $ELLICAST_CORPUS, e.g. a
checkout of KhronosGroup/glTF-Sample-Assets/Models). Progress goes to stderr, the table to
OUT_DIR/corpus.md, the raw figures to OUT_DIR/corpus.json.
"""
import json
import os
import struct
import subprocess
import sys
import time


def gltf_json(path):
    """The JSON of a .gltf file or of a GLB's JSON chunk."""
    with open(path, 'rb') as f:
        data = f.read()
    if data[:4] == b'glTF':
        length = struct.unpack('<I', data[12:16])[0]
        return json.loads(data[20:20 + length])
    return json.loads(data)


def files_of(path, doc):
    """Bytes of the file and of every external buffer and image it names."""
    total = os.path.getsize(path)
    folder = os.path.dirname(path)
    for key in ('buffers', 'images'):
        for item in doc.get(key, []):
            uri = item.get('uri', '')
            if uri and not uri.startswith('data:'):
                try:
                    total += os.path.getsize(os.path.join(folder, uri))
                except OSError:
                    pass
    return total


def census(doc):
    morph = sum(1 for m in doc.get('meshes', []) for p in m.get('primitives', []) if p.get('targets'))
    return {
        'nodes': len(doc.get('nodes', [])),
        'materials': len(doc.get('materials', [])),
        'images': len(doc.get('images', [])),
        'animations': len(doc.get('animations', [])),
        'channels': sum(len(a.get('channels', [])) for a in doc.get('animations', [])),
        'skins': len(doc.get('skins', [])),
        'morph': morph,
        'extensions': sorted(doc.get('extensionsUsed', [])),
    }


def validate(path, node_modules):
    """The Khronos validator's [errors, warnings, warning codes] for a file, or None without it."""
    check = subprocess.run(['node', os.path.join(os.path.dirname(__file__), '..', 'tests', 'gltf_validate.js'), path],
                           capture_output=True, text=True, env=dict(os.environ, NODE_PATH=node_modules))
    try:
        verdict = json.loads(check.stdout)
        return [verdict.get('numErrors'), verdict.get('numWarnings'), sorted(set(verdict.get('warnings', [])))]
    except ValueError:
        return None


def main():
    ellicast, node_modules, out_dir = sys.argv[1:4]
    folders = sys.argv[4:]
    assets = []  # (label: the path below its folder, path), folder by folder
    for folder in folders:
        found = []
        for root, _, names in os.walk(folder):
            for name in names:
                if name.lower().endswith(('.gltf', '.glb')):
                    path = os.path.join(root, name)
                    found.append((os.path.relpath(path, folder), path))
        assets += sorted(found)
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for i, (label, path) in enumerate(assets):
        print(f'[{i + 1}/{len(assets)}] {label}', file=sys.stderr, flush=True)
        out = os.path.join(out_dir, 'out', label.replace(os.sep, '_') + '.glb')
        os.makedirs(os.path.dirname(out), exist_ok=True)
        row = {'asset': label}
        try:
            doc_in = gltf_json(path)
            row['in_bytes'] = files_of(path, doc_in)
            row['in'] = census(doc_in)
        except (OSError, ValueError) as e:
            row['error'] = f'unreadable: {e}'
            rows.append(row)
            continue
        start = time.monotonic()
        run = subprocess.run([ellicast, 'convert', '-q', path, out], capture_output=True, text=True)
        row['seconds'] = round(time.monotonic() - start, 2)
        row['exit'] = run.returncode
        row['warnings'] = [l[len('ellicast: warning: '):] for l in run.stderr.splitlines() if l.startswith('ellicast: warning: ')]
        if run.returncode != 0:
            row['error'] = (run.stderr.strip().splitlines() or ['?'])[-1]
            rows.append(row)
            continue
        for line in run.stdout.splitlines():
            if line.startswith('stream: '):
                row['stream_bytes'] = int(line.split(', ')[-1].split()[0])
        row['out_bytes'] = os.path.getsize(out)
        row['out'] = census(gltf_json(out))
        row['validator'] = validate(out, node_modules)
        row['validator_in'] = validate(path, node_modules)
        rows.append(row)

    with open(os.path.join(out_dir, 'corpus.json'), 'w') as f:
        json.dump(rows, f, indent=1)

    def pair(row, key):
        a, b = row['in'][key], row['out'][key]
        return f'{a}' if a == b else f'**{a} -> {b}**'

    lines = ['| asset | in / stream / out (KB) | time (s) | validator errors / warnings (of the output) | nodes | materials | images | '
             'animations (channels) | skins | morph prims | dropped or changed (warnings) |',
             '|---|---|---:|---|---|---|---|---|---|---|---|']
    for row in rows:
        if 'error' in row:
            lines.append(f"| {row['asset']} | {row.get('in_bytes', 0) / 1024:.0f} / - / - | {row.get('seconds', '-')} | "
                         f"not converted | | | | | | | {row['error']} |")
            continue
        v, s = row['validator'], row.get('validator_in')
        verdict = f'{v[0]} / {v[1]}' + (f" ({', '.join(v[2])})" if v[2] else '') if v else 'validator absent'
        if v and s and v[2]:
            # Say whether the source has the same warnings (a faithful copy keeps a source's quirks).
            verdict += '; the source has ' + ('them too' if set(v[2]) <= set(s[2]) else ', '.join(s[2]) or 'none')
        warnings = '; '.join(w.split(': ', 1)[-1] for w in row['warnings'])
        if len(warnings) > 300:
            warnings = warnings[:297] + '...'
        anim = f"{row['in']['animations']} ({row['in']['channels']})"
        anim_out = f"{row['out']['animations']} ({row['out']['channels']})"
        lines.append(
            f"| {row['asset']} | {row['in_bytes'] / 1024:.0f} / {row.get('stream_bytes', 0) / 1024:.0f} / "
            f"{row['out_bytes'] / 1024:.0f} | {row['seconds']} | {verdict} | {pair(row, 'nodes')} | "
            f"{pair(row, 'materials')} | {pair(row, 'images')} | {anim if anim == anim_out else f'**{anim} -> {anim_out}**'} | "
            f"{pair(row, 'skins')} | {pair(row, 'morph')} | {warnings} |")
    with open(os.path.join(out_dir, 'corpus.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
