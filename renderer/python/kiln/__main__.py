"""python -m kiln ARGS (and the `kiln` script pip installs): the kiln command line, the binary the
package carries in kiln/bin/. The process becomes kiln, so exit codes, signals and Ctrl-C are the
CLI's own and kiln batch's jobs start the same binary."""
import os
import sys
from pathlib import Path


def binary():
    """The kiln executable installed with this package."""
    return Path(__file__).resolve().parent / "bin" / "kiln"


def main():
    path = binary()
    if not os.access(path, os.X_OK):
        sys.exit(f"kiln: {path}: the command-line binary is missing from the installed package")
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(path, ["kiln"] + sys.argv[1:])


if __name__ == "__main__":
    main()
