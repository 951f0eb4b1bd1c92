"""`python -m goalagent` runs the command-line interface."""

from goalagent.cli import main

main()
