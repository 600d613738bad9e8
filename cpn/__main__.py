"""`python -m cpn` runs the `cpn-verify` command line."""

from cpn.cli.main import entry

entry()
