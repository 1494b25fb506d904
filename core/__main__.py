"""`python -m core render scene.lua`: see core.cli."""

import sys

from .cli import main

sys.exit(main())
