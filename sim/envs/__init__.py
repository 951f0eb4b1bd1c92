"""EIS environments built on the simulated world (the `garbage` environment)."""
