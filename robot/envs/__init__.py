"""EIS environments over the MuJoCo worlds: `garbage` (ch. 5-6), `navigation` and `stacking`
(ch. 3), `search` (App. A); the ch. 4-5 task worlds join here."""
