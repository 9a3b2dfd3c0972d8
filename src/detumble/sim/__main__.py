"""``python -m detumble.sim`` - plant-only run; see :mod:`detumble.sim.runner`."""

import sys

from detumble.sim.runner import main

if __name__ == "__main__":
    sys.exit(main())
