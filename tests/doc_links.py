#!/usr/bin/env python3
"""Every relative link in the project's Markdown resolves: the file exists and, for `page.md#anchor`,
the page has a heading with that anchor as a forge (GitHub, GitLab) derives it. External links are
not fetched. Prints each broken link as `file:line: target (why)` and exits 1 if there is one.

    python3 tests/doc_links.py [ROOT]
"""
import pathlib
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^()\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*(```|~~~)")
SKIPPED_DIRS = {".git", "build", "node_modules"}


def prose_lines(text):
    """(line number, line) outside fenced code blocks, with inline code spans blanked out."""
    inside = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield number, re.sub(r"`[^`]*`", lambda m: " " * len(m.group(0)), line)


def anchor(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`", "", heading.strip().lower())
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(page):
    seen = {}
    found = set()
    inside = False
    for line in page.read_text(encoding="utf-8").splitlines():
        if FENCE.match(line):
            inside = not inside
            continue
        heading = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if inside or not heading:
            continue
        base = anchor(heading.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        found.add(base if count == 0 else f"{base}-{count}")
    return found


def broken_links(root):
    for page in sorted(root.rglob("*.md")):
        if SKIPPED_DIRS.intersection(page.relative_to(root).parts):
            continue
        for number, line in prose_lines(page.read_text(encoding="utf-8")):
            for match in LINK.finditer(line):
                target = match.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                path, _, fragment = target.partition("#")
                resolved = (page.parent / path).resolve() if path else page
                where = f"{page.relative_to(root)}:{number}: {target}"
                if not resolved.exists():
                    yield f"{where} (no such file)"
                elif fragment and resolved.suffix == ".md" and fragment not in anchors(resolved):
                    yield f"{where} (no heading with that anchor in {resolved.relative_to(root)})"


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent).resolve()
    broken = list(broken_links(root))
    for line in broken:
        print(line)
    pages = sum(1 for p in root.rglob("*.md") if not SKIPPED_DIRS.intersection(p.relative_to(root).parts))
    print(f"doc_links: {len(broken)} broken link(s) in {pages} Markdown file(s)")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
