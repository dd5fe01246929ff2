#!/usr/bin/env python3
"""Lists MuJoCo's compiler and XML-reader refusals from a MuJoCo source checkout.

Usage:
  tools/mujoco_refusals.py MUJOCO_SRC [--lib LIBMUJOCO [--lib-only]] [--catalog CATALOG_TSV]

Finds every `throw mjCError(...)` (and `SetError(mjCError(...))`, the errors the
spec API keeps for the reader to relay) in src/user/*.cc, every `throw mjXError(...)`
in src/xml/*.cc and the schema's own messages (`error = "..."` in xml_util.cc), and prints one TSV row per distinct message (file, first line,
message): the message is the format string, adjacent string literals joined, as
MuJoCo passes it to its printf (`%s`, `%d` stand for the names and numbers it fills
in). A message built at run time (`"%s"` with a computed string) is listed as
`<dynamic>`.

With --lib, each message is looked up in the strings of that MuJoCo library (the
pinned 4.0.0 wheel's libmujoco.so): the `in_lib` column says whether the library
holds it (a message of the source that the library lacks was reworded or added
after that release; the library's wording decides).

With --lib-only (and --lib), prints instead the strings of the library that read
like refusals (a rule word such as "must be", "cannot", "invalid", "requires") and
match no message of the source: messages of the release that the source checkout
lacks (a checkout older than the release, or reworded). Library internals (qhull,
PNG and zlib codecs, the unwinder, the engine's runtime checks, "Invalid model: X
too large") are left out. They are candidates to review and add to the catalog as
rows of file `libmujoco.so.4.0.0`.

With --catalog, the classification columns of an existing catalog (class, note) are
carried over to messages still present, new messages are marked `unclassified`, and
catalog rows whose message is gone are reported on stderr (rows of the library's
own, whose file is not under src/, are kept): the way to redo the catalog for a new
MuJoCo version.
"""

import csv
import re
import subprocess
import sys
from pathlib import Path

FILES = [('src/user', 'mjCError'), ('src/xml', 'mjXError')]
LITERAL = re.compile(r'"((?:[^"\\]|\\.)*)"')


def call_text(src, start):
    """The text of the call whose '(' is at start, up to its matching ')'."""
    depth, i, in_str = 0, start, False
    while i < len(src):
        c = src[i]
        if in_str:
            if c == '\\':
                i += 1
            elif c == '"':
                in_str = False
        elif c == '"':
            in_str = True
        elif c == '(':
            depth += 1
        elif c == ')':
            depth -= 1
            if depth == 0:
                return src[start + 1:i]
        i += 1
    return src[start + 1:]


def concatenation(expr):
    """A string expression's literals, with %s for each value between them
    (`string("a '") + name + "'"` gives `a '%s'`)."""
    out = []
    chunks = re.split(r'"((?:[^"\\]|\\.)*)"', expr)
    for k, chunk in enumerate(chunks):
        if k % 2:
            out.append(bytes(chunk, 'utf-8').decode('unicode_escape'))
            continue
        rest = re.sub(r'(std::)?string\(|\.c_str\(\)|\.data\(\)|[()+,\s]', '', chunk)
        if rest and len(chunks) > 1:
            out.append('%s')
    return ''.join(out)


def message(args):
    """The format string of an error call's arguments (after the object)."""
    # Skip the first argument (the object or element), then join the literals that
    # follow it until the first non-literal argument.
    depth, i = 0, 0
    while i < len(args):
        c = args[i]
        if c in '([':
            depth += 1
        elif c in ')]':
            depth -= 1
        elif c == ',' and depth == 0:
            break
        i += 1
    rest = args[i + 1:].lstrip()
    parts = []
    while True:
        m = LITERAL.match(rest)
        if not m:
            break
        parts.append(m.group(1))
        rest = rest[m.end():].lstrip()
    text = ''.join(parts)
    if text == '%s' and rest.startswith(','):
        # "%s" with a string concatenated in the call.
        if LITERAL.search(rest):
            return concatenation(rest[1:])
    if not parts and LITERAL.search(rest):
        # A string expression in place of the format.
        return concatenation(rest)
    if not parts or text == '%s':
        return '<dynamic>'
    return bytes(text, 'utf-8').decode('unicode_escape')


BUILD = re.compile(r'(stringstream\s+\w+|string\s+\w+\s*=)')


def built_message(before):
    """A message built at run time in the lines before its throw (a stringstream or
    a string concatenation): its literals joined by %s, else <dynamic>."""
    for k in range(len(before) - 1, -1, -1):
        if BUILD.search(before[k]):
            text = ' '.join(line.strip() for line in before[k:])
            # The expression: after the `=`, or a stream's `<<` pieces, up to its `;`.
            if 'stringstream' in text:
                # The statements `ss << a << b;` after the declaration.
                text = ' + '.join(re.findall(r'<<([^;]*);', text))
            else:
                text = text.split('=', 1)[1] if '=' in text.split('"')[0] else text
                text = text.split(';')[0]
            if LITERAL.search(text):
                return concatenation(text.replace('<<', '+'))
            break
    return '<dynamic>'


def extract(root):
    rows, seen = [], set()
    for folder, fn in FILES:
        for path in sorted((root / folder).glob('*.cc')):
            src = path.read_text(encoding='utf-8', errors='replace')
            pattern = r'(?:throw\s+|SetError\()' + fn + r'\s*\('
            for m in re.finditer(pattern, src):
                open_paren = m.end() - 1
                msg = message(call_text(src, open_paren))
                line = src.count('\n', 0, m.start()) + 1
                if msg == '<dynamic>':
                    msg = built_message(src.splitlines()[max(0, line - 12):line - 1])
                rel = str(path.relative_to(root))
                key = (rel, msg) if msg == '<dynamic>' else msg
                if msg == '<dynamic>':
                    key = (rel, line)
                if key in seen:
                    continue
                seen.add(key)
                rows.append((rel, line, msg))
    # The schema's checks (xml_util.cc): messages MuJoCo's reader gives as
    # "Schema violation: ..." (an unknown element or attribute, attributes that
    # exclude or require each other).
    util = root / 'src/xml/xml_util.cc'
    src = util.read_text(encoding='utf-8', errors='replace')
    for m in re.finditer(r'\b(?:error = |sprintf_arr\(msg, )([^;]*);', src):
        parts = LITERAL.findall(m.group(1))
        if not parts:
            continue
        msg = 'Schema violation: ' + '%s'.join(parts)
        tail = m.group(1).rstrip()
        if not m.group(0).startswith('sprintf') and not tail.endswith('"'):
            msg += '%s'
        if msg in seen:
            continue
        seen.add(msg)
        rows.append(('src/xml/xml_util.cc', src.count('\n', 0, m.start()) + 1, msg))
    return rows


def in_library(msg, strings):
    """Whether the library's strings hold msg (each piece between format specifiers
    of 6 characters or more is looked for)."""
    if msg == '<dynamic>':
        return ''
    body = msg.removeprefix('Schema violation: ')
    pieces = [p for p in re.split(r'%[-0-9.]*[sdfgiu]', body) if len(p.strip()) >= 6]
    if not pieces:
        return ''
    return 'yes' if all(any(p in s for s in strings) for p in pieces) else 'no'


RULE = re.compile(r'(must be|cannot|not allowed|requires|require |invalid|unknown|not found|'
                  r'too large|too small|must have|should be|is required|not supported|'
                  r'unrecognized|repeated|mismatch|only|negative|positive)')
INTERNAL = re.compile(
    r'^(Invalid model|Invalid data|[Qq]hull|qh_|mjui_|mjb_|mjv|mjr_|mjc_|DW_EH|WARNING|libunwind|'
    r'Format string|stl_decoder|obj_decoder|\(|%s: |XML Write)|chunk|PNG|zlib|palette|ICC|sRGB|'
    r'encoder|inflating|CRC|ADLER|BTYPE|idat|filter strateg|window size|pHYs|gAMA|tIME|bKGD|cICP|'
    r'tRNS|CFA|register|locale|island|nefc|nsim|Hessian|ccd|color conversion|colortype|'
    r'grayscale|constant metric|pair type|unknown error code|sensor stage|stage, sensor|'
    r'sensor id|actuator id|actuator index|object type %d|body %d|invalid tree|invalid index|'
    r'state|srcsig|frustum|perspective and orthographic|shortcut|rownnz|sleep|ipc|IPC|RK4|'
    r'integrator|solver|inverse dynamics|delays are not|problem size|vector length|'
    r'fill-in|nonzeroes|cannot be saved|MJCF cannot|saved file|mjSpec-only|cannot be written|'
    r'must be compiled to be saved|attribute ignored|full dimensional|warning type|times must be')


def library_only(strings, rows):
    """The library's refusal-like strings that no message of `rows` matches."""
    pieces = set()
    for _, _, msg in rows:
        for p in re.split(r'%[-0-9.]*[sdfgiu]', msg.removeprefix('Schema violation: ')):
            if len(p.strip()) >= 6:
                pieces.add(p.strip())
    out, seen = [], set()
    for s in strings:
        s = s.strip()
        if s in seen or not 8 < len(s) < 200 or ' ' not in s:
            continue
        seen.add(s)
        if RULE.search(s) and not INTERNAL.search(s) and not any(p in s or s in p for p in pieces):
            out.append(s)
    return out


def main():
    args = sys.argv[1:]
    if not args or args[0].startswith('-'):
        sys.exit(__doc__)
    root = Path(args[0])
    lib = args[args.index('--lib') + 1] if '--lib' in args else None
    catalog = args[args.index('--catalog') + 1] if '--catalog' in args else None
    rows = extract(root)
    strings = None
    if lib:
        out = subprocess.run(['strings', '-n', '6', lib], capture_output=True, text=True)
        strings = out.stdout.splitlines()
    if '--lib-only' in args:
        if strings is None:
            sys.exit('--lib-only needs --lib')
        for s in library_only(strings, rows):
            print(s)
        return
    known = {}
    if catalog:
        with open(catalog, newline='') as f:
            for r in csv.DictReader(f, delimiter='\t', quoting=csv.QUOTE_NONE):
                known[(r['file'], r['message'])] = r

    class Rows:
        """Tab-separated rows, unquoted (no message holds a tab or a newline)."""

        @staticmethod
        def writerow(row):
            print('\t'.join(str(x) for x in row))

    w = Rows()
    header = ['file', 'line', 'message']
    if strings is not None:
        header.append('in_lib')
    if catalog:
        header += ['class', 'note', 'case']
    w.writerow(header)
    present = set()
    for rel, line, msg in rows:
        row = [rel, line, msg]
        if strings is not None:
            row.append(in_library(msg, strings))
        if catalog:
            k = known.get((rel, msg))
            present.add((rel, msg))
            row += [k['class'], k['note'], k['case']] if k else ['unclassified', '', '']
        w.writerow(row)
    for k, r in known.items():
        if k in present:
            continue
        if not k[0].startswith('src/'):
            # A row of the library's own (found with --lib-only): kept as it is.
            row = [r['file'], r['line'], r['message']]
            if strings is not None:
                row.append(in_library(r['message'], strings))
            w.writerow(row + [r['class'], r['note'], r['case']])
            continue
        print(f'gone: {k[0]}: {k[1]}', file=sys.stderr)


if __name__ == '__main__':
    main()
