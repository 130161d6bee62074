"""python -m dpend.explore MAP.h5: see dpend.explore."""
import sys

from . import main

sys.exit(main())
