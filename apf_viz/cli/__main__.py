"""``python -m apf_viz.cli``: the same as ``apf-viz``."""

import sys

from apf_viz.cli import main

sys.exit(main())
