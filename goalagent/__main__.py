"""`python -m goalagent` runs the command-line interface (signals handled from the start)."""

from goalagent.launcher import main

main()
