#!/usr/bin/env python3
"""Checks that the repository's documentation refers only to what the repository holds.

Fails (exit 1, one line per problem) on:
- a Markdown link in README.md or docs/ whose target file or #anchor does not exist;
- a backticked path in README.md or docs/ that names no file: looked up from the repository root,
  then from src/steadylight/; a bare file name (no folder) may be anywhere in the repository.
  Paths under build/ or out/, absolute paths, and names holding <, * or { are placeholders or
  outputs and are skipped;
- a comment in code, a script or a build file naming a Markdown document that does not exist,
  or a section of it (`docs/x.md, "Title"`) that it has no heading for.

    python3 scripts/check_docs.py [--root DIR]
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

PATH_SUFFIXES = ('.h', '.cpp', '.md', '.json', '.sh', '.py', '.mjs', '.glb', '.gltf', '.exr', '.png',
                 '.txt', '.in', '.cmake', '.obj', '.hdr', '.blend')
LINK = re.compile(r'(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)')
CODE_SPAN = re.compile(r'(`+)(.+?)\1')
FENCE = re.compile(r'^\s*(```|~~~)')
DOC_IN_COMMENT = re.compile(r'(?:[\w./-]*[\w-]\.md\b|\bREADME\b)(?:,? \\?"([^"\\]+)\\?")?')
CODE_SUFFIXES = ('.h', '.cpp', '.py', '.sh', '.mjs', '.cmake', '.txt', '.in')


def tracked_files(root):
    out = subprocess.run(['git', 'ls-files'], cwd=root, capture_output=True, text=True, check=True).stdout
    return [Path(line) for line in out.splitlines() if (root / line).exists()]


def github_anchors(markdown):
    """The anchors GitHub gives a page's headings: lower case, punctuation dropped, spaces to '-'."""
    anchors, seen, in_fence = set(), {}, False
    for line in markdown.splitlines():
        if FENCE.match(line):
            in_fence = not in_fence
        if in_fence:
            continue
        heading = re.match(r'^#{1,6}\s+(.*?)\s*#*\s*$', line)
        if not heading:
            continue
        text = re.sub(r'[`*]|\[([^\]]*)\]\([^)]*\)', lambda m: m.group(1) or '', heading.group(1))
        slug = re.sub(r'[^\w\- ]', '', text.lower()).replace(' ', '-')
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        anchors.add(slug if n == 0 else f'{slug}-{n}')
    return anchors


def heading_titles(page):
    """The titles of a page's headings, in lower case."""
    return {m.group(1).strip().lower() for m in re.finditer(r'^#{1,6}\s+(.*?)\s*#*\s*$', page.read_text(), re.M)}


def prose_lines(markdown):
    """(line number, text) of the lines outside fenced code blocks."""
    in_fence = False
    for number, line in enumerate(markdown.splitlines(), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if not in_fence:
            yield number, line


def check_link(root, page, target, problems, where):
    if re.match(r'^[a-z]+:', target) or target.startswith('//'):
        return  # a URL or mailto: outside the repository's reach
    file_part, _, anchor = target.partition('#')
    path = (page.parent / file_part).resolve() if file_part else page.resolve()
    if not path.exists():
        problems.append(f'{where}: link to {target}: no such file')
    elif anchor and path.suffix == '.md' and anchor not in github_anchors(path.read_text()):
        problems.append(f'{where}: link to {target}: no heading with that anchor')


def looks_like_path(token):
    if re.search(r'\s', token) or not re.fullmatch(r'[\w.\-/+#]+', token) or token.startswith('-'):
        return False
    if re.fullmatch(r'\.\w+', token):
        return False  # a file type such as `.glb`, not a file
    return '/' in token.strip('/') or token.endswith(PATH_SUFFIXES)


def check_code_path(root, token, names, problems, where):
    if re.search(r'[<*{]', token) or token.startswith(('/', '~', 'build', 'out/')):
        return
    path = token.split('#')[0].rstrip('/')
    if path.startswith(('build-', './build')) or not path:
        return
    if (root / path).exists() or (root / 'src/steadylight' / path).exists():
        return
    if '/' not in path and path in names:
        return
    problems.append(f'{where}: `{token}` names no file in the repository')


def check_markdown(root, page, names, problems):
    text = page.read_text()
    for number, line in prose_lines(text):
        where = f'{page.relative_to(root)}:{number}'
        for match in LINK.finditer(CODE_SPAN.sub('', line)):
            check_link(root, page, match.group(1) or match.group(2), problems, where)
        for match in CODE_SPAN.finditer(line):
            if looks_like_path(match.group(2)):
                check_code_path(root, match.group(2), names, problems, where)


def comment_text(path, line):
    """The comment part of a line of code, script or build file ('' when it has none)."""
    marker = '//' if path.suffix in ('.h', '.cpp', '.mjs') else '#'
    index = line.find(marker)
    return line[index:] if index >= 0 else ''


def check_comments(root, path, problems):
    for number, line in enumerate((root / path).read_text(errors='replace').splitlines(), 1):
        for match in DOC_IN_COMMENT.finditer(comment_text(path, line)):
            doc = match.group(0)
            if re.search(r'[<*{]', doc) or doc.startswith(('build/', 'out/')):
                continue
            doc = re.sub(r'^README$', 'README.md', re.split(r',| ', doc)[0])
            candidates = [c for c in (root / doc, root / 'docs' / doc, (root / path).parent / doc) if c.exists()]
            if not candidates:
                problems.append(f'{path}:{number}: comment names {doc}, which does not exist')
            elif match.group(1) and match.group(1).lower() not in heading_titles(candidates[0]):
                problems.append(f'{path}:{number}: comment names section "{match.group(1)}" of {doc}, which has none')


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--root', default=Path(__file__).resolve().parent.parent, type=Path)
    root = parser.parse_args().root.resolve()
    files = tracked_files(root)
    names = {f.name for f in files}
    problems = []
    for page in files:
        if page.suffix == '.md' and (page == Path('README.md') or page.parts[0] == 'docs'):
            check_markdown(root, root / page, names, problems)
        elif page.suffix in CODE_SUFFIXES or page.name == 'CMakeLists.txt':
            check_comments(root, page, problems)
    for problem in problems:
        print(problem)
    print(f'check_docs: {len(problems)} problem(s)' if problems else 'check_docs: every reference resolves')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
