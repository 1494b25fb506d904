"""`python -m core render scene.lua`: see core.cli."""

import sys

from core.cli import main

sys.exit(main())
