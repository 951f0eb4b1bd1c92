"""goalagent package."""
