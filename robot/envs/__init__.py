"""EIS environments over the MuJoCo worlds (the `garbage` environment; the ch.3-5 task worlds
join here)."""
