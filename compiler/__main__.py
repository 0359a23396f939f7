"""`python -m rfc`: the same command line as the `rfc` script."""

from rfc.cli import main

main()
