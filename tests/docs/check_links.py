#!/usr/bin/env python3
"""Every relative link and image in README.md and docs/*.md names a file that exists, and every
#anchor a heading of the page it points into (GitHub's anchors: lower case, punctuation dropped,
spaces as dashes, -1, -2, ... for repeats). Links inside code are not links and are skipped.

Usage: check_links.py SOURCE_DIR
"""

import glob
import os
import re
import sys
import unittest

SOURCE = sys.argv[1] if len(sys.argv) > 1 else "."
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def prose_lines(path):
    """(line number, line) outside fenced code blocks, with inline code spans blanked."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if not fenced:
                yield number, re.sub(r"`[^`]*`", "``", line)


def anchors(path):
    """The anchors GitHub gives the headings of a Markdown file."""
    seen, found, fenced = {}, set(), False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.lstrip().startswith("```"):
                fenced = not fenced
            match = None if fenced else re.match(r"^#{1,6} +(.*?)\s*#*\s*$", line)
            if not match:
                continue
            text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", match.group(1))  # a link's text only
            slug = re.sub(r"[^\w\- ]", "", text.lower()).replace(" ", "-")
            count = seen.get(slug, 0)
            seen[slug] = count + 1
            found.add(slug if count == 0 else "%s-%d" % (slug, count))
    return found


def broken_links(path):
    """'file:line: target: why' for each link of path that does not resolve."""
    problems = []
    for number, line in prose_lines(path):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:
                continue
            file_part, _, anchor = target.partition("#")
            linked = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            where = "%s:%d: %s" % (os.path.relpath(path, SOURCE), number, target)
            if not os.path.exists(linked):
                problems.append(where + ": no such file")
            elif anchor and linked.endswith(".md") and anchor not in anchors(linked):
                problems.append(where + ": no heading with that anchor")
    return problems


def pages():
    return [os.path.join(SOURCE, "README.md")] + sorted(glob.glob(os.path.join(SOURCE, "docs", "*.md")))


class links(unittest.TestCase):
    def test_every_relative_link_resolves(self):
        problems = [p for page in pages() for p in broken_links(page)]
        self.assertEqual(problems, [], "\n" + "\n".join(problems))

    def test_the_checker_sees_a_broken_file_and_anchor(self):
        page = os.path.join(SOURCE, "docs", "rendering.md")
        self.assertIn("anti-aliasing", anchors(page))
        self.assertIn("checking-embree-against-the-grid-kiln-compare", anchors(page))
        self.assertGreaterEqual(sum(1 for page in pages() for _ in prose_lines(page)), 1000)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
