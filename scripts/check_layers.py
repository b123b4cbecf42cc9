#!/usr/bin/env python3
"""Checks that no include runs up the layers (docs/architecture.md): a file under
src/steadylight/LAYER/ includes only from its own folder and the layers listed before it;
render.{h,cpp} sit above them all. Tests follow the same rule, so a test that needs a higher
layer lives there (or in tests/, above every layer). Exit 1, one line per include, when any
runs up.

    python3 scripts/check_layers.py [--root DIR]
"""
import argparse
import re
import sys
from pathlib import Path

LAYERS = ['base', 'scene', 'trace', 'shading', 'photons', 'irradiance', 'passes', 'methods', 'quality',
          'output', 'run', 'report', 'farm']
INCLUDE = re.compile(r'^\s*#\s*include\s+"steadylight/([a-z_]+)/')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--root', default=Path(__file__).resolve().parent.parent, type=Path)
    root = parser.parse_args().root
    problems = []
    for layer_index, layer in enumerate(LAYERS):
        for path in sorted((root / 'src/steadylight' / layer).glob('*.[hc]*')):
            for number, line in enumerate(path.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if match and match.group(1) in LAYERS and LAYERS.index(match.group(1)) > layer_index:
                    problems.append(f'{path.relative_to(root)}:{number}: includes from {match.group(1)}/, '
                                    f'a layer above {layer}/')
    for problem in problems:
        print(problem)
    print(f'check_layers: {len(problems)} include(s) run up the layers' if problems
          else 'check_layers: no include runs up the layers')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
