#!/usr/bin/env python3
"""Real glTF assets through `ellicast convert`: sizes, time, the Khronos validator's verdict, and
what of the scene comes back: feature by feature (kept, lost with a warning that names it, lost
silently) and counted (nodes, materials, images, animations, skins, morph targets), as a Markdown
table.

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


STORAGE_EXTENSIONS = ('KHR_draco_mesh_compression', 'KHR_mesh_quantization', 'EXT_meshopt_compression')
TEXTURE_SLOTS = ('baseColorTexture', 'metallicRoughnessTexture', 'normalTexture', 'occlusionTexture', 'emissiveTexture')


def features(doc):
    """The scene of `doc` feature by feature, as {description: word}: the word a warning about the
    feature's loss must contain (as tests/test_catalogue_features.cpp has them)."""
    out = {}
    nodes = doc.get('nodes', [])
    scenes = doc.get('scenes', [])
    if scenes:
        s = doc.get('scene', 0)
        stack = list(scenes[s if s < len(scenes) else 0].get('nodes', []))
    else:
        stack = list(range(len(nodes)))
    reached = set()
    while stack:
        i = stack.pop()
        if not isinstance(i, int) or i in reached or not 0 <= i < len(nodes):
            continue
        reached.add(i)
        n = nodes[i]
        stack += n.get('children', [])
        name = n.get('name', '')
        if name:
            out['node ' + name] = name
        if 'camera' in n:
            out['a camera on node ' + name] = 'camera'
        if 'KHR_lights_punctual' in n.get('extensions', {}):
            out['a light on node ' + name] = 'light'
        if 'extras' in n:
            out['extras of node %s: %s' % (name, json.dumps(n['extras'], sort_keys=True))] = 'extras'
    for c in doc.get('cameras', []):
        out['camera %s %s' % (c.get('type', ''), c.get('name', ''))] = 'camera'
    for l in doc.get('extensions', {}).get('KHR_lights_punctual', {}).get('lights', []):
        out['light %s %s' % (l.get('type', ''), l.get('name', ''))] = 'light'
    for m in doc.get('materials', []):
        name = m.get('name', '?')
        out['material ' + name] = name
        for ext in m.get('extensions', {}):
            out['material %s %s' % (name, ext)] = ext
        pbr = m.get('pbrMetallicRoughness', {})
        for slot in TEXTURE_SLOTS:
            info = pbr.get(slot) or m.get(slot)
            if info:
                out['material %s %s on TEXCOORD_%d' % (name, slot, info.get('texCoord', 0))] = slot
                for ext in info.get('extensions', {}):
                    out['material %s %s %s' % (name, slot, ext)] = ext
        if 'extras' in m:
            out['extras of material ' + name] = 'extras'
    for m in doc.get('meshes', []):
        name = m.get('name', '?')
        for p in m.get('primitives', []):
            for attribute in p.get('attributes', {}):
                out['mesh %s %s' % (name, attribute)] = attribute
            if p.get('targets'):
                out['mesh %s %d morph targets' % (name, len(p['targets']))] = 'target'
        if 'extras' in m:
            out['extras of mesh %s: %s' % (name, json.dumps(m['extras'], sort_keys=True))] = 'extras'
    for a in doc.get('animations', []):
        for c in a.get('channels', []):
            t = c.get('target', {})
            node = t.get('node', -1)
            on = nodes[node].get('name', str(node)) if isinstance(node, int) and 0 <= node < len(nodes) else '-'
            out['animation %s %s of %s' % (a.get('name', ''), t.get('path', ''), on)] = 'animation'
    for k in doc.get('skins', []):
        out['skin %s of %d joints' % (k.get('name', ''), len(k.get('joints', [])))] = 'skin'
    # How the geometry is stored (Draco, quantized, meshopt) is not a feature of the scene: an object the
    # output cannot store that way (morph targets stay plain) shows in the size ratio, not here.
    for e in doc.get('extensionsUsed', []):
        if e not in STORAGE_EXTENSIONS:
            out['uses ' + e] = e
    for e in doc.get('extensionsRequired', []):
        if e not in STORAGE_EXTENSIONS:
            out['requires ' + e] = e
    if 'extras' in doc.get('asset', {}):
        out['extras of the asset'] = 'extras'
    return out


def compare(doc_in, doc_out, warnings):
    """Features of the input kept by the output, lost with a warning naming them, lost silently."""
    a, b = features(doc_in), features(doc_out)
    kept = [f for f in a if f in b]
    lost = [f for f in a if f not in b]
    named = [f for f in lost if any(a[f] in w for w in warnings)]
    return {'features': len(a), 'kept': len(kept), 'named': sorted(named),
            'silent': sorted(f for f in lost if f not in named)}


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
        doc_out = gltf_json(out)
        row['out'] = census(doc_out)
        row['features'] = compare(doc_in, doc_out, row['warnings'])
        row['validator'] = validate(out, node_modules)
        row['validator_in'] = validate(path, node_modules)
        rows.append(row)

    with open(os.path.join(out_dir, 'corpus.json'), 'w') as f:
        json.dump(rows, f, indent=1)

    def pair(row, key):
        a, b = row['in'][key], row['out'][key]
        return f'{a}' if a == b else f'**{a} -> {b}**'

    lines = ['| asset | in / stream / out (KB) | out / in | time (s) | validator errors / warnings (of the output) | features kept '
             '/ lost with a warning / lost silently | nodes | materials | images | animations (channels) | skins | morph prims | '
             'dropped or changed (warnings) |',
             '|---|---|---:|---:|---|---|---|---|---|---|---|---|---|']
    for row in rows:
        if 'error' in row:
            lines.append(f"| {row['asset']} | {row.get('in_bytes', 0) / 1024:.0f} / - / - | | {row.get('seconds', '-')} | "
                         f"not converted | | | | | | | | {row['error']} |")
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
        f = row['features']
        kept = f"{f['kept']} of {f['features']} / {len(f['named'])} / " + (
            f"**{len(f['silent'])}: {'; '.join(f['silent'])}**" if f['silent'] else '0')
        lines.append(
            f"| {row['asset']} | {row['in_bytes'] / 1024:.0f} / {row.get('stream_bytes', 0) / 1024:.0f} / "
            f"{row['out_bytes'] / 1024:.0f} | {row['out_bytes'] / row['in_bytes']:.2f} | {row['seconds']} | {verdict} | {kept} | "
            f"{pair(row, 'nodes')} | "
            f"{pair(row, 'materials')} | {pair(row, 'images')} | {anim if anim == anim_out else f'**{anim} -> {anim_out}**'} | "
            f"{pair(row, 'skins')} | {pair(row, 'morph')} | {warnings} |")
    done = [r for r in rows if 'error' not in r]
    ratios = sorted(r['out_bytes'] / r['in_bytes'] for r in done)
    errors = sum((r['validator'] or [0])[0] or 0 for r in done)
    silent = sum(len(r['features']['silent']) for r in done)
    larger = [r['asset'] for r in done if r['out_bytes'] > 1.1 * r['in_bytes']]
    lines += ['', f"{len(rows)} assets, {len(done)} converted; validator errors in the outputs: {errors}; features lost "
                  f"silently: {silent}; outputs over 1.1x their input: {len(larger)}"
                  + (f" ({', '.join(larger)})" if larger else '')
                  + (f"; output / input: median {ratios[len(ratios) // 2]:.2f}, largest {ratios[-1]:.2f}" if ratios else '')]
    with open(os.path.join(out_dir, 'corpus.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print('\n'.join(lines))


if __name__ == '__main__':
    main()
