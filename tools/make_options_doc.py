#!/usr/bin/env python3
"""Write docs/options.md, every option of every kiln command grouped as `kiln render --help` groups
them, from kiln's own option table: the page is what `kiln help --markdown` prints.

Usage: make_options_doc.py [--kiln KILN] [--page PAGE] [--check]

KILN defaults to the build's binary (build/renderer/app/kiln). --check writes nothing and exits 1
when the page differs from what KILN prints, which the test docs.options_page_is_current runs so
the page cannot drift from the option table; after changing an option, run this script.
"""

import argparse
import difflib
import os
import subprocess
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_KILN = os.path.join(SOURCE, "build", "renderer", "app", "kiln")
DEFAULT_PAGE = os.path.join(SOURCE, "docs", "options.md")


def generated(kiln):
    """The page as kiln prints it."""
    return subprocess.run([kiln, "help", "--markdown"], check=True, capture_output=True, text=True).stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--kiln", default=DEFAULT_KILN, help="the kiln binary (default: the build's)")
    parser.add_argument("--page", default=DEFAULT_PAGE, help="the page to write (default: docs/options.md)")
    parser.add_argument("--check", action="store_true", help="exit 1 when the page differs instead of writing it")
    args = parser.parse_args()
    text = generated(args.kiln)
    if args.check:
        with open(args.page, encoding="utf-8") as f:
            page = f.read()
        if page != text:
            diff = difflib.unified_diff(page.splitlines(), text.splitlines(), args.page, "kiln help --markdown",
                                        lineterm="", n=0)
            sys.stderr.write("\n".join(list(diff)[:20]) + "\n")
            sys.exit("%s: out of date with the option table; run tools/make_options_doc.py" % args.page)
        return
    with open(args.page, "w", encoding="utf-8") as f:
        f.write(text)


if __name__ == "__main__":
    main()
