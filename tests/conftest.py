"""Settings of the whole test suite."""

import os

# The suite builds many small libraries (one per net whose C it tests): `-O1` compiles them in about a third
# less time than the `-O2` users get (cpn._util.cbuild.cflags); what the tests check does not depend on it.
os.environ.setdefault("CPN_CC_OPT", "-O1")
