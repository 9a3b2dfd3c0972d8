"""A module that takes 1.5 s to import (the probe kind's ``slow_import`` mode: a first run's imports)."""

import time

time.sleep(1.5)
