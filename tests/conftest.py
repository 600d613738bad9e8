"""Settings of the whole test suite."""

import os

# The suite builds many small libraries (one per net whose C it tests), and what the tests check does not
# depend on the optimisation: it builds them without (`-O0`, not the `-O2` users get from
# cpn._util.cbuild.cflags). A library of DP(6) compiled in 0.23 s at -O0, 0.58 s at -O1; the whole suite from
# a fresh clone and an empty cache took 7 min 14 s at -O0 and 8 min 10 s at -O1, the slower searches included.
os.environ.setdefault("CPN_CC_OPT", "-O0")
