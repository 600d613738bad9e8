"""Where the shared test data lives: `../shared` beside the repository (CI's layout), or CPN_SHARED_DIR."""

import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("CPN_SHARED_DIR") or os.path.normpath(os.path.join(ROOT, "..", "shared"))
