#!/usr/bin/env python3
"""Keep the TeX in Rust doc comments intact through rustdoc's Markdown.

rustdoc renders doc comments as Markdown before KaTeX (docs/katex-header.html) sees the page, and
Markdown treats a backslash before ASCII punctuation as an escape: `$a\\,b$` written with one
backslash reaches KaTeX as `a,b`, `\\{` as `{`, TeX's line break `\\\\` as a single backslash. An
underscore next to punctuation (`}_k ... y_{0}`) can also open or close emphasis. So inside
`$...$` and `$$...$$` (outside code spans and fenced blocks) the sources write:

- `\\\\,` for TeX's `\\,` (every backslash before punctuation doubled), `\\\\\\\\` for TeX's `\\\\`;
- `\\_` for an underscore next to punctuation or a space, `\\*` for an asterisk.

    python3 tools/doc_tex.py --check   # CI: list violations, exit 1 if any
    python3 tools/doc_tex.py --fix     # rewrite the files in place (idempotent)

Run from the repository root; it reads every tracked `*.rs` file.
"""
import pathlib, re, subprocess, sys

PUNCT = set('!"#$%&\'()*+,-./:;<=>?@[\\]^_`{|}~')
DOC = re.compile(r'^(\s*//[/!] ?)(.*)$')


def fix_math(s):
    """The Markdown-safe form of the TeX in `s` (already-safe text is returned unchanged)."""
    out, i = [], 0
    while i < len(s):
        c = s[i]
        if c == '\\':
            j = i
            while j < len(s) and s[j] == '\\':
                j += 1
            k, nxt = j - i, (s[j] if j < len(s) else '')
            if nxt in ('_', '*') and k == 1:
                pass              # `\_`: an underscore already escaped for Markdown
            elif nxt in PUNCT and nxt and k % 2 == 1:
                k *= 2            # raw `\,` -> `\\,`
            elif nxt not in PUNCT and k % 4 == 2:
                k *= 2            # raw TeX line break `\\` -> `\\\\`
            out.append('\\' * k)
            if nxt in ('_', '*'):
                out.append(nxt)   # an escaped `_`/`*` (`\_`) stays as written
                j += 1
            i = j
            continue
        if c == '*' or (c == '_' and (
                (i > 0 and (s[i - 1] in PUNCT or s[i - 1].isspace()))
                or (i + 1 < len(s) and (s[i + 1] in PUNCT or s[i + 1].isspace())))):
            out.append('\\' + c)
        else:
            out.append(c)
        i += 1
    return ''.join(out)


def process(text):
    lines = text.split('\n')
    new, fence, math = list(lines), False, None
    for n, line in enumerate(lines):
        m = DOC.match(line)
        if not m:
            fence, math = False, None
            continue
        prefix, content = m.groups()
        if content.lstrip().startswith('```'):
            fence = not fence
            continue
        if fence:
            continue
        res, i, code = [], 0, False
        while i < len(content):
            c = content[i]
            if math is None and c == '`':
                code = not code
            if code or (math is None and c != '$'):
                if math is None and c == '\\' and i + 1 < len(content):
                    res.append(content[i:i + 2])
                    i += 2
                    continue
                res.append(c)
                i += 1
                continue
            if c == '$':
                delim = '$$' if content.startswith('$$', i) else '$'
                if math is None:
                    math = delim
                elif math == '$$' and delim == '$':
                    res.append(c)
                    i += 1
                    continue
                else:
                    delim, math = math, None
                res.append(delim)
                i += len(delim)
                continue
            j = i
            while j < len(content) and content[j] != '$':
                j += 1
            res.append(fix_math(content[i:j]))
            i = j
        new[n] = prefix + ''.join(res)
    return '\n'.join(new)


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else '--check'
    files = subprocess.run(['git', 'ls-files', '*.rs'], capture_output=True, text=True,
                           check=True).stdout.split()
    bad = []
    for name in files:
        path = pathlib.Path(name)
        old = path.read_text()
        fixed = process(old)
        if fixed != old:
            if mode == '--fix':
                path.write_text(fixed)
            for k, (a, b) in enumerate(zip(old.split('\n'), fixed.split('\n'))):
                if a != b:
                    bad.append(f'{name}:{k + 1}: {a.strip()}')
    if mode == '--check' and bad:
        print('TeX in doc comments that Markdown would eat (fix: python3 tools/doc_tex.py --fix):')
        print('\n'.join(bad[:40]))
        sys.exit(1)
    print(f'{len(bad)} line(s) {"fixed" if mode == "--fix" else "to fix"} in {len(files)} files')


if __name__ == '__main__':
    main()
