"""Pure learners (thesis chapters 3–5): numpy / scikit-learn only, no MuJoCo, no agents.

Chapter 3 and Appendix A (task learning with affordances): ``xcs`` (Wilson's accuracy-based
classifier system XCS with Algorithm 2's action filter, and ``XCSClassifier``, its
scikit-learn face), built from ``xcs_agent``, ``xcs_population``, ``xcs_discovery``,
``xcs_params`` and ``xcs_persistence``.

Chapter 4 (active affordance learning): ``network`` (the small tanh network), ``forward_model``
(F_ψ, eq. 4.1–4.4), ``cacla`` (actor-critic and the TD-error stop test, eq. 4.5–4.11),
``convergence`` ((4.10) on a recorded TD-error series, beside labelled variants that are
not the thesis's), ``exploration`` (Algorithm 3 and the random baseline over a
``ContinuousWorld``), ``skill_acquisition`` (goal generation and paired skills,
eq. 4.12–4.18); ``validation`` and ``persist`` (versioned JSON files, written
atomically) serve them all.

Chapter 5 (part-based affordance models and transfer): ``part_models`` (ĝ, ĥ, 5.9–5.12),
``protocol`` (the object under test), ``baseline`` (Algorithm 4), ``similarity``
(Algorithm 5), ``transfer`` (Algorithm 6), ``known_objects`` (the known-object database).

Chapter 6 (the garbage disposal robot): ``effect_models`` (Ĥ(θ), eq. 6.7, and its store).

``tags`` declares the domain limits scikit-learn has no tag for (binary inputs, bounded
actions).
"""
