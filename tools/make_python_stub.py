#!/usr/bin/env python3
"""Fill the options block of the kiln package's type stubs (renderer/python/kiln/__init__.pyi).

Usage: PYTHONPATH=build/python make_python_stub.py [STUB.pyi] [--check]

Every option of `kiln render` (kiln.options()) becomes a field of the TypedDict RenderOptions,
which render(), render_sequence() and info() take as **options, with its Python type (a Literal
of its choices where it has them; None keeps the default) and its help as the field's docstring,
so an IDE completes every keyword with its type and help. Only the lines between "# BEGIN
options" and "# END options" are written. --check exits 1 when they differ from what the module
gives, which tests/python runs so the stub cannot drift from the option table.
"""

import argparse
import os
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_STUB = os.path.join(SOURCE, "renderer", "python", "kiln", "__init__.pyi")
BEGIN, END = "# BEGIN options\n", "# END options\n"


def annotation(option):
    """The field's type: None keeps the default."""
    choices = option["choices"]
    if choices:
        literal = "Literal[%s]" % ", ".join(repr(c) for c in choices)
        # An on/off choice also takes a bool (packets=True).
        return "Optional[Union[%s, bool]]" % literal if "on" in choices else "Optional[%s]" % literal
    return "Optional[%s]" % {"int": "int", "float": "float", "bool": "bool"}.get(option["type"], "_Text")


def options_block(kiln):
    """The RenderOptions TypedDict of the module kiln as imported."""
    lines = ["class RenderOptions(TypedDict, total=False):"]
    for option in kiln.options():
        given = option["default"] not in (None, "") and "default" not in option["help"]
        default = " (default %s)" % option["default"] if given else ""
        doc = "%s: %s%s" % (option["option"], option["help"], default)
        lines.append("    %s: %s" % (option["name"], annotation(option)))
        lines.append('    """%s"""' % doc.replace("\\", "\\\\").replace('"', '\\"'))
    return "\n".join(lines) + "\n"


def updated(stub, kiln):
    """stub with its options block generated again."""
    start, end = stub.index(BEGIN) + len(BEGIN), stub.index(END)
    return stub[:start] + options_block(kiln) + stub[end:]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("stub", nargs="?", default=DEFAULT_STUB, help="the stub file (default: the package's)")
    parser.add_argument("--check", action="store_true", help="exit 1 when the block differs instead of writing it")
    args = parser.parse_args()
    import kiln  # noqa: E402 (the module on PYTHONPATH, not necessarily an installed one)
    with open(args.stub) as f:
        stub = f.read()
    text = updated(stub, kiln)
    if args.check:
        if text != stub:
            sys.exit("%s: the options block is out of date; run tools/make_python_stub.py" % args.stub)
        return
    with open(args.stub, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
