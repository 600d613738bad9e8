"""Settings of the whole test suite."""

import os

# The suite builds many small libraries (one per net whose C it tests), and what the tests check does not
# depend on the optimisation: it builds them without (`-O0`, not the `-O2` users get from
# cpn._util.cbuild.cflags). A library of DP(6) compiled in 0.23 s at -O0 and 0.58 s at -O1 (gcc 12, two runs
# each). Whole runs of the suite from a fresh clone and an empty cache varied more than that difference on
# the same machine: 7 min 14 s and 8 min 45 s at -O0, 8 min 10 s at -O1.
os.environ.setdefault("CPN_CC_OPT", "-O0")
