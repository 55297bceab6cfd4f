"""`python -m robotdesc`: the same as the `robotdesc` command."""

import sys

from robotdesc.cli import main

if __name__ == "__main__":
    sys.exit(main())
