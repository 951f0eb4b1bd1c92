"""XCS, Wilson's accuracy-based learning classifier system (thesis Appendix A, §3.3.3-3.3.4).

Why goalagent has its own: `xcsf` chooses the action itself in its multi-step interface, so
Algorithm 2's affordance filter (eq. 3.10) cannot sit between its prediction array and its
choice, and it has none of the thesis's variants; `xcs` and `scikit-XCS` keep one Python object
per classifier and are slow (bench/xcs.py measures all three against this one).

- `XCS`: the agent-facing learner — ``act(state, explore, allowed)``, ``reward(r, done)``,
  ``end_trial()``, ``prediction_array(state)``, ``classifiers()``, ``save``/``load``;
  single- and multi-step problems, the thesis's consistent-actions exploration, GA and
  action-set subsumption (`behaviours/learners/xcs_agent.py`).
- `XCSClassifier`: the scikit-learn face for single-step classification over binary features.
- `Classifier`: one macro-classifier record.

The algorithm follows Butz & Wilson, "An algorithmic description of XCS" (2001); the modules
behind it: `xcs_population` (the classifiers as numpy arrays, vectorised matching),
`xcs_discovery` (the match set and covering, GA, subsumption, deletion), `xcs_choice` (the
action chosen), `xcs_update` (UPDATE SET, eq. 7.1-7.7), `xcs_inputs` (a step's arguments
checked), `xcs_params` (the parameters' scikit-learn constraints), `xcs_persistence`.
"""

from .xcs_agent import XCS
from .xcs_classifier import XCSClassifier
from .xcs_population import Classifier

__all__ = ["XCS", "Classifier", "XCSClassifier"]
