#!/usr/bin/env python3
"""Bad scene and machine files, tried against vmt as a careful reviewer would.

Every scalar, list and map of every scene in scenes/ and of every machine.yaml in models/ is
replaced, one at a time, by a wrong type or an absurd value; vmt runs the result for a moment.
Each try must end in one of two ways: vmt accepts it (the value was fine after all), or it
refuses it with exit 2 and a message that names the file. A crash, a hang, a raw library text
or a refusal that does not say where is a failure.

The tries are all the replacements in a fixed order shuffled by --seed, run until --budget-s or
--count is reached, so a run is repeatable and --only K repeats one try. The report lands in
OUT/bad_inputs.json and a line on stdout.

  bad_inputs.py VMT SRC OUT [--budget-s 90] [--count N] [--only K] [--seed 1] [--jobs 2]
"""

import argparse
import concurrent.futures
import json
import os
import random
import re
import shutil
import subprocess
import sys
import time

import yaml

# What a value may be replaced with: the wrong types, and numbers no machine has.
SCALAR_REPLACEMENTS = [
    '"text"', '[]', '{}', '~', '""', '-1', '0', '1.5', '.nan', '.inf', '-.inf', '1e308',
    '-1e308', '99999999999999999999', '"\\u00e9\\u00df\\u2603"',
]
COLLECTION_REPLACEMENTS = ['"text"', '7', '~', '[]', '{}', '[[[[[[1]]]]]]']
RAW = re.compile(r"yaml-cpp|json\.exception|\bsto[idlf]\b|basic_filebuf|filesystem error|"
                 r"terminate called|what\(\)|std::|bad_alloc|bad conversion|invalid node|"
                 r"AddressSanitizer|runtime error:|Segmentation|core dumped")


def places(text):
    """(start, end, path, kind) of every node below the document's root."""
    found = []

    def walk(node, path):
        if isinstance(node, yaml.MappingNode):
            for key, value in node.value:
                sub = f"{path}.{key.value}" if path else str(key.value)
                found.append((value.start_mark.index, value.end_mark.index, sub,
                              'scalar' if isinstance(value, yaml.ScalarNode) else 'collection'))
                walk(value, sub)
        elif isinstance(node, yaml.SequenceNode):
            for i, value in enumerate(node.value):
                sub = f"{path}[{i}]"
                found.append((value.start_mark.index, value.end_mark.index, sub,
                              'scalar' if isinstance(value, yaml.ScalarNode) else 'collection'))
                walk(value, sub)

    root = yaml.compose(text)
    if root is not None:
        walk(root, '')
    return found


def is_flow(text, start, end):
    """A flow collection ([...], {...}) is replaced where it stands; a block one spans lines."""
    return text[start:start + 1] in ('[', '{')


def tries(src):
    """Every (kind, file, start, end, path, replacement), in a fixed order."""
    out = []
    targets = [('scene', os.path.join('scenes', f)) for f in sorted(os.listdir(os.path.join(src, 'scenes')))
               if f.endswith('.yaml') and not f.startswith('.')]
    targets += [('model', os.path.join('models', d, 'machine.yaml'))
                for d in sorted(os.listdir(os.path.join(src, 'models')))
                if os.path.isfile(os.path.join(src, 'models', d, 'machine.yaml'))]
    for kind, rel in targets:
        text = open(os.path.join(src, rel), encoding='utf-8').read()
        for start, end, path, node in places(text):
            end = start + len(text[start:end].rstrip())  # the next line stays whole
            if node == 'collection' and not is_flow(text, start, end):
                if path.endswith(']'):
                    continue  # a block item of a list: its own values are tried
                # A block list or map: replaced as a whole after its key, on the key's line.
                start = text.rfind(':', 0, start) + 1
                replacements = [' ' + r for r in COLLECTION_REPLACEMENTS]
            else:
                replacements = SCALAR_REPLACEMENTS if node == 'scalar' else COLLECTION_REPLACEMENTS
            for r in replacements:
                out.append((kind, rel, start, end, path, r))
    return out


def prepare(src, work):
    """A tree beside the sources: scenes/ and models/ entries linked, so that a mutated file
    written there finds what its original refers to."""
    os.makedirs(os.path.join(work, 'scenes'), exist_ok=True)
    for entry in os.listdir(os.path.join(src, 'scenes')):
        if not entry.endswith('.yaml'):
            link = os.path.join(work, 'scenes', entry)
            if not os.path.lexists(link):
                os.symlink(os.path.join(src, 'scenes', entry), link)
    for top in ('models', 'examples'):
        link = os.path.join(work, top)
        if not os.path.lexists(link) and os.path.isdir(os.path.join(src, top)):
            os.symlink(os.path.join(src, top), link)


def scene_for_model(src, model_dir):
    """A scene of the repository on that model: the first whose model: names it."""
    name = os.path.basename(model_dir)
    for f in sorted(os.listdir(os.path.join(src, 'scenes'))):
        if f.endswith('.yaml') and not f.startswith(('study', '.')):
            text = open(os.path.join(src, 'scenes', f), encoding='utf-8').read()
            if re.search(rf'^model:\s*\.\./models/{re.escape(name)}/machine\.yaml\s*$', text, re.M):
                return f, text
    return None, None


def run_one(args, work, index, t):
    kind, rel, start, end, path, replacement = t
    original = open(os.path.join(args.src, rel), encoding='utf-8').read()
    mutated = original[:start] + replacement + original[end:]
    folder = os.path.join(work, 'tries', str(index))
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    if kind == 'scene':
        scene = os.path.join(work, 'scenes', f'try-{index}.yaml')
        named = f'try-{index}.yaml'
        open(scene, 'w', encoding='utf-8').write(mutated)
    else:
        model_src = os.path.join(args.src, os.path.dirname(rel))
        model_dir = os.path.join(work, 'models-tried', str(index), os.path.basename(model_src))
        os.makedirs(model_dir, exist_ok=True)
        for entry in os.listdir(model_src):
            if entry != 'machine.yaml':
                os.symlink(os.path.join(model_src, entry), os.path.join(model_dir, entry))
        open(os.path.join(model_dir, 'machine.yaml'), 'w', encoding='utf-8').write(mutated)
        scene_name, scene_text = scene_for_model(args.src, model_src)
        if scene_name is None:
            return None
        scene_text = re.sub(r'^model:.*$', f'model: {os.path.join(model_dir, "machine.yaml")}',
                            scene_text, count=1, flags=re.M)
        scene = os.path.join(work, 'scenes', f'try-{index}.yaml')
        named = 'machine.yaml'
        open(scene, 'w', encoding='utf-8').write(scene_text)
    command = [args.vmt, 'run', scene, '--until', '0.05', '--out', os.path.join(folder, 'out')]
    began = time.monotonic()
    try:
        p = subprocess.run(command, capture_output=True, timeout=args.timeout_s)
        code, output = p.returncode, (p.stdout + p.stderr).decode('utf-8', 'replace')
    except subprocess.TimeoutExpired as e:
        code, output = None, ((e.stdout or b'') + (e.stderr or b'')).decode('utf-8', 'replace')
    seconds = time.monotonic() - began
    if code is None:
        verdict = 'hang'
    elif code < 0 or code >= 128:
        verdict = 'crash'
    elif RAW.search(output):
        verdict = 'raw'
    elif code == 2:
        verdict = 'refused' if named in output else 'unplaced'
    else:
        verdict = 'accepted'
    shutil.rmtree(folder, ignore_errors=True)
    if os.path.exists(scene):
        os.remove(scene)
    if kind == 'model':
        shutil.rmtree(os.path.join(work, 'models-tried', str(index)), ignore_errors=True)
    return {'try': index, 'file': rel, 'path': path, 'value': replacement.strip(), 'exit': code,
            'verdict': verdict, 'seconds': round(seconds, 3), 'output': output[-600:]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('vmt')
    ap.add_argument('src')
    ap.add_argument('out')
    ap.add_argument('--budget-s', type=float, default=90)
    ap.add_argument('--count', type=int, default=0, help='stop after this many tries (0: budget)')
    ap.add_argument('--only', type=int, default=-1, help='run only try K')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--timeout-s', type=float, default=20)
    args = ap.parse_args()
    args.vmt, args.src, args.out = (os.path.abspath(p) for p in (args.vmt, args.src, args.out))
    shutil.rmtree(args.out, ignore_errors=True)
    work = os.path.join(args.out, 'work')
    prepare(args.src, work)
    order = tries(args.src)
    indices = list(range(len(order)))
    random.Random(args.seed).shuffle(indices)
    if args.only >= 0:
        indices = [args.only]
    elif args.count > 0:
        indices = indices[:args.count]
    began = time.monotonic()
    results = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        pending = set()
        queue = iter(indices)
        while True:
            while len(pending) < args.jobs and time.monotonic() - began < args.budget_s:
                i = next(queue, None)
                if i is None:
                    break
                pending.add(pool.submit(run_one, args, work, i, order[i]))
            if not pending:
                break
            done, pending = concurrent.futures.wait(
                pending, return_when=concurrent.futures.FIRST_COMPLETED)
            results += [f.result() for f in done if f.result() is not None]
    results.sort(key=lambda r: r['try'])
    counts = {v: sum(r['verdict'] == v for r in results)
              for v in ('accepted', 'refused', 'unplaced', 'raw', 'crash', 'hang')}
    failures = [r for r in results if r['verdict'] in ('unplaced', 'raw', 'crash', 'hang')]
    seconds = time.monotonic() - began
    report = {'tries_possible': len(order), 'tried': len(results), 'seconds': round(seconds, 1),
              'seed': args.seed, 'counts': counts, 'failures': failures,
              'accepted': [{k: r[k] for k in ('try', 'file', 'path', 'value', 'exit')}
                           for r in results if r['verdict'] == 'accepted']}
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, 'bad_inputs.json'), 'w') as f:
        json.dump(report, f, indent=1)
    shutil.rmtree(work, ignore_errors=True)
    print(f"bad inputs: {len(results)} of {len(order)} tried in {seconds:.0f} s (seed {args.seed}): "
          f"{counts['refused']} refused naming the file, {counts['accepted']} accepted, "
          f"{counts['unplaced']} refused without the file, {counts['raw']} raw texts, "
          f"{counts['crash']} crashes, {counts['hang']} hangs")
    for r in failures[:20]:
        print(f"FAIL try {r['try']} ({r['verdict']}, exit {r['exit']}): {r['file']} {r['path']} = "
              f"{r['value']}\n    " + r['output'].strip().replace('\n', '\n    ')[-400:])
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
