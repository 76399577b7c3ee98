# SPDX-License-Identifier: LGPL-2.1-or-later
"""``python3 -m facet``: the Facet command line (see :mod:`facet.cli`)."""

import sys

from facet.cli import main

if __name__ == "__main__":
    sys.exit(main())
