"""``goalagent reproduce NAME``: named reproductions of the thesis's (and the literature's)
tables and figures, each a module of this package.

Adding one, say ``ch5-transfer``:

1. Write ``robot/reproduce/ch5_transfer.py`` (the name with ``-`` as ``_``) defining
   ``REPRODUCTION = Reproduction(name="ch5-transfer", description="one line", run_seed=...,
   summarize=..., compare=..., figures=..., notes="...")`` with module-level functions:

   - ``run_seed(seed, scale, progress) -> dict``: one independent run. Seed every random
     generator from ``seed``; shrink the run with ``scale`` (1 is the source's full size, the
     test suite runs ``quick_scale``); call ``progress(fraction)`` now and then. Return plain
     JSON (numbers, lists, dicts, None for a missing value): every number the run measured
     and the curves to plot.
   - ``summarize(seeds) -> dict``: the aggregate figures the issue names (the ``summary``
     object of ``NAME.json``).
   - ``compare(summary, seeds) -> list[Comparison]``: rows of ``NAME.md``'s table, each a
     measured value (mean, sd over seeds) beside the thesis's or literature's value and its
     source; the gap is computed for you.
   - ``figures(seeds) -> list[Figure]``: panels of ``Series`` (one list per seed; the plot
     shows mean ± sd) and ``Reference`` lines for the thesis's values.
   - optionally ``listings(summary, seeds) -> str``: markdown after the notes, for tables
     that depend on what was measured (learned rules, an affordance table beside the
     thesis's); pass it as ``listings=``.

   Keep the module's top-level imports light (``--list`` imports every module); import
   MuJoCo and friends inside ``run_seed``.
2. Add a test that runs it at ``quick_scale`` with two seeds (see ``tests/test_reproduce.py``).
3. Run it in full, ``nice -n 10 goalagent reproduce ch5-transfer --out docs/results``, and
   commit the JSON, markdown and PNGs.

The framework (``framework``: the declarations and the lookup by name; ``runner``: seeds in
parallel processes with a progress bar, the outputs written atomically; ``report``: the
markdown table and the plots) knows nothing of any particular reproduction.
"""
