#!/usr/bin/env python3
"""Derive the facts of MuJoCo's own MJCF schema (`src/xml/mjcf.schema` of
google-deepmind/mujoco) as one table the crate's tests read:

    python3 tools/mjcf_schema_facts.py MUJOCO_CHECKOUT/src/xml/mjcf.schema \
        > schema/mjcf-schema-facts.tsv

One row per attribute of every element as it appears under each parent (the XML tag of
the parent and of the element: `body geom`, `default geom`, `sensor jointpos`), with its
type (`double[1..3]`, `ref<body>`, `enum<geomtype>`, ...) and its facets (`required`,
`min=`, `max=`, `positive`, `nodefault`, `pattern=`); and one row per presence rule
(`exclusive`, `together`, `requires`, `oneof`, and a `variant` group's attributes, which
exclude each other). Parents that MuJoCo's schema gives the grammar of a body (the
world body, frames, replicates: `alias=body`) are written `(world)body`, as the crate's
other schema files write them.
"""
import re
import sys


def parse(text):
    groups, elements = {}, {}
    cur = None
    for raw in text.splitlines():
        line = raw.split('#', 1)[0].rstrip()
        if not line.strip():
            continue
        m = re.match(r'^(group|element|enum)\s+(\S+)(.*)\{\s*$', line)
        if m:
            kind, name, rest = m.groups()
            if kind == 'enum':
                cur = None
                continue
            facets = re.search(r'\(([^)]*)\)', rest)
            facets = facets.group(1) if facets else ''
            entry = {'name': name, 'attrs': [], 'rules': [], 'children': [],
                     'variant': 'variant' in rest.split(':')[0],
                     'xml': (re.search(r'xml=(\w+)', facets) or re.search(r'()', '')).group(1) or name,
                     'alias': (re.search(r'alias=(\w+)', facets) or re.search(r'()', '')).group(1)}
            (groups if kind == 'group' else elements)[name] = entry
            cur = entry
            continue
        if line.strip() == '}':
            cur = None
            continue
        if cur is None:
            continue
        words = line.split()
        if words[0] == 'use':
            cur['attrs'].append(('use', words[1]))
        elif words[0] == 'child':
            cur['children'].append((words[1], words[2] if len(words) > 2 else '?'))
        elif words[0] in ('exclusive', 'together', 'requires', 'oneof'):
            cur['rules'].append((words[0], ' '.join(words[1:])))
        else:
            m = re.match(r'^\s*(\w+)\s*:\s*(\S+)(?:\s*=\s*(\{[^}]*\}|\S+))?\s*(?:\(([^)]*)\))?', line)
            if m:
                name, ty, _default, facets = m.groups()
                keep = [f.strip() for f in (facets or '').split(',')
                        if f.strip().split('=')[0] in ('required', 'min', 'max', 'positive', 'nodefault', 'pattern')]
                cur['attrs'].append((name, ty, ' '.join(keep)))
    return groups, elements


def attrs_of(entry, groups):
    out, rules = [], []
    for a in entry['attrs']:
        if a[0] == 'use':
            g = groups[a[1]]
            sub, subrules = attrs_of(g, groups)
            out += sub
            rules += subrules
            if g['variant']:
                rules.append(('exclusive', ' '.join(x[0] for x in sub)))
        else:
            out.append(a)
    return out, rules + entry['rules']


def main():
    groups, elements = parse(open(sys.argv[1]).read())
    body_like = {n for n, e in elements.items() if e['alias'] == 'body'} | {'body'}
    print('# Derived from MuJoCo\'s src/xml/mjcf.schema by tools/mjcf_schema_facts.py; do not edit.')
    print('parent\telement\tattribute\ttype\tfacets')
    seen = set()
    for pname, parent in elements.items():
        ptag = '(world)body' if pname in body_like else parent['xml']
        for child, _card in parent['children']:
            # The root's `body` child is the world body (whose grammar is a body's):
            # its elements appear under `(world)body`.
            if child not in elements or (pname == 'mujoco' and child == 'body'):
                continue
            e = elements[child]
            key = (ptag, e['xml'], child)
            if key in seen:
                continue
            seen.add(key)
            attrs, rules = attrs_of(e, groups)
            for name, ty, facets in attrs:
                print(f"{ptag}\t{e['xml']}\t{name}\t{ty}\t{facets}")
            for rule, what in rules:
                print(f"{ptag}\t{e['xml']}\t\t{rule}\t{what}")


if __name__ == '__main__':
    main()
