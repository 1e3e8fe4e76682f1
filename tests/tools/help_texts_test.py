#!/usr/bin/env python3
"""The --help of every script under tools/ and bench/ whose argparse description comes from its
docstring shows the docstring's whole first paragraph (the first line alone stopped mid-sentence).
A script whose imports are missing here (bpy, the kiln module before it is built) is skipped.

Usage: help_texts_test.py SOURCE_DIR
"""

import ast
import os
import subprocess
import sys
import unittest

SOURCE = sys.argv[1]


def described_by_docstring():
    """(path, the docstring's first paragraph) of each script whose parser takes description=__doc__."""
    for folder in ("tools", "bench"):
        for root, _, names in os.walk(os.path.join(SOURCE, folder)):
            for name in sorted(names):
                path = os.path.join(root, name)
                if not name.endswith(".py"):
                    continue
                text = open(path, encoding="utf-8").read()
                if "description=__doc__" in text:
                    yield path, ast.get_docstring(ast.parse(text)).split("\n\n")[0]


def words(text):
    return " ".join(text.split())


class help_texts(unittest.TestCase):
    def test_the_docstrings_first_paragraph_is_shown_whole(self):
        checked = 0
        for script, paragraph in described_by_docstring():
            done = subprocess.run([sys.executable, script, "--help"], capture_output=True, text=True, timeout=60)
            if "ModuleNotFoundError" in done.stderr:
                print(f"skipped {os.path.relpath(script, SOURCE)}: {done.stderr.splitlines()[-1]}")
                continue
            with self.subTest(script=os.path.relpath(script, SOURCE)):
                self.assertEqual(done.returncode, 0, done.stderr)
                self.assertIn(words(paragraph), words(done.stdout))
                checked += 1
        self.assertGreaterEqual(checked, 10)  # the tools' own scripts at least


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
