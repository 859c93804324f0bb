#!/usr/bin/python3
# Checks the relative links of README.md and docs/*.md: every markdown link or image (and HTML href/src)
# whose target is not http(s)://, mailto: or another scheme must name a file or folder that exists, and a
# target with a #anchor must name a heading of the target file (GitHub's slugs: lower case, punctuation
# other than '-' and '_' dropped, spaces to '-', repeats suffixed -1, -2, ...). Links inside fenced code
# blocks and inline code are ignored. Prints "FILE: broken link TARGET" per broken link; exits 1 if any.
# Usage: scripts/check_doc_links.py [FILE.md ...]   (standard library only; run from anywhere)
import os
import re
import sys
import urllib.parse

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
# [text](target "title") or ![alt](target), text allowing one level of nested brackets.
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^\s()]*(?:\([^\s()]*\)[^\s()]*)*)(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)")
REFERENCE_DEF = re.compile(r"^ {0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)", re.MULTILINE)
HTML_LINK = re.compile(r"<(?:a|img)\b[^>]*?\b(?:href|src)\s*=\s*[\"']([^\"']*)[\"']", re.IGNORECASE)
INLINE_CODE = re.compile(r"(`+)(.+?)(?<!`)\1(?!`)", re.DOTALL)


def strip_fenced(text):
    """The text with fenced code blocks blanked (lines kept, so nothing shifts)."""
    out, fence = [], None
    for line in text.split("\n"):
        m = FENCE.match(line)
        if fence is None and m:
            fence = m.group(1)[0] * len(m.group(1))
            out.append("")
        elif fence is not None:
            if m and m.group(1).startswith(fence):
                fence = None
            out.append("")
        else:
            out.append(line)
    return "\n".join(out)


def slug(heading_text):
    """GitHub's anchor for a heading's text (markdown markup reduced to the rendered text first)."""
    text = re.sub(r"!?\[((?:[^\[\]]|\[[^\[\]]*\])*)\]\([^)]*\)", r"\1", heading_text)  # links: their text
    text = re.sub(r"<[^>]+>", "", text)  # HTML tags
    text = text.replace("`", "").replace("*", "")
    text = text.lower()
    text = "".join(c for c in text if c.isalnum() or c in "-_ ")
    return text.replace(" ", "-")


_anchor_cache = {}


def anchors(path):
    if path not in _anchor_cache:
        found, seen = set(), {}
        with open(path, encoding="utf-8") as f:
            text = strip_fenced(f.read())
        for line in text.split("\n"):
            m = HEADING.match(line)
            if not m:
                continue
            base = slug(m.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else "%s-%d" % (base, n))
        # Explicit anchors: <a name="x"> or id="x".
        for m in re.finditer(r"<a\s+(?:name|id)\s*=\s*[\"']([^\"']+)[\"']", text):
            found.add(m.group(1))
        _anchor_cache[path] = found
    return _anchor_cache[path]


def targets(text):
    text = strip_fenced(text)
    text = INLINE_CODE.sub(lambda m: " " * len(m.group(0)), text)
    for regex in (INLINE_LINK, REFERENCE_DEF, HTML_LINK):
        for m in regex.finditer(text):
            target = m.group(1).strip()
            if target.startswith("<") and target.endswith(">"):
                target = target[1:-1]
            yield target


def broken_links(md_path):
    with open(md_path, encoding="utf-8") as f:
        text = f.read()
    for target in targets(text):
        if not target or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):  # http:, https:, mailto:, ...
            continue
        path_part, _, anchor = target.partition("#")
        path_part = urllib.parse.unquote(path_part)
        if path_part:
            if path_part.startswith("/"):
                dest = os.path.join(ROOT, path_part.lstrip("/"))
            else:
                dest = os.path.normpath(os.path.join(os.path.dirname(md_path), path_part))
        else:
            dest = md_path
        if not os.path.exists(dest):
            yield target
        elif anchor and (not dest.endswith(".md") or os.path.isdir(dest) or
                         urllib.parse.unquote(anchor) not in anchors(dest)):
            yield target


def main(argv):
    if argv:
        files = [os.path.abspath(a) for a in argv]
    else:
        docs = os.path.join(ROOT, "docs")
        files = [os.path.join(ROOT, "README.md")]
        if os.path.isdir(docs):
            files += sorted(os.path.join(docs, n) for n in os.listdir(docs) if n.endswith(".md"))
    broken = 0
    for md in files:
        for target in broken_links(md):
            print("%s: broken link %s" % (os.path.relpath(md, ROOT), target))
            broken += 1
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
