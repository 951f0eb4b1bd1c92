"""XCS's parameters as a study config (Butz & Wilson 2001; thesis App. A, Table 7.1), shared by
every study that runs XCS: each sets the defaults its source used, and ``--set mu=0.02`` or
``--grid p_hash=0.33,0.5`` reaches the learner unchanged."""

from __future__ import annotations

from typing import Annotated

from pydantic import Field

from robot.reproduce.framework import ScaledConfig

Rate = Annotated[float, Field(gt=0.0, le=1.0)]
Probability = Annotated[float, Field(ge=0.0, le=1.0)]
Positive = Annotated[float, Field(gt=0.0)]
NonNegative = Annotated[float, Field(ge=0.0)]
Count = Annotated[int, Field(ge=0)]


class XcsParameters(ScaledConfig):
    """XCS's parameters; the defaults are the learner's own (Wilson's multiplexer settings)."""

    N: Annotated[int, Field(ge=1)] = 400
    """Population size N: the most micro-classifiers (App. A, Table 7.1)."""
    beta: Rate = 0.2
    """Learning rate β of prediction, error and fitness (eqs 7.3-7.5) where β_p, β_ε, β_F are
    not given."""
    beta_p: Rate | None = None
    """Learning rate of the prediction (eq. 7.3, Table 7.1's β_p); None: β."""
    beta_e: Rate | None = None
    """Learning rate of the prediction error (eq. 7.4, Table 7.1's β_ε); None: β."""
    beta_f: Rate | None = None
    """Learning rate of the fitness (eq. 7.5, Table 7.1's β_F); None: β."""
    gamma: Probability = 0.71
    """Discount factor γ of the payoff (eq. 7.2)."""
    alpha: Rate = 0.1
    """Accuracy fall-off α (eq. 7.6)."""
    epsilon_0: Positive = 10.0
    """Error ε0 under which a classifier counts as accurate (eq. 7.6)."""
    nu: Positive = 5.0
    """Accuracy exponent ν (eq. 7.6)."""
    theta_ga: Count = 25
    """GA threshold θGA: the mean time since the action set's last GA before it runs again."""
    chi: Probability = 0.8
    """Crossover probability χ."""
    mu: Probability = 0.04
    """Mutation probability μ per allele."""
    theta_del: Count = 20
    """Deletion threshold θdel: experience after which low fitness raises the deletion vote."""
    delta: Probability = 0.1
    """Fraction δ of the mean fitness below which the deletion vote grows."""
    theta_sub: Count = 20
    """Subsumption threshold θsub: experience a subsumer needs."""
    p_hash: Probability = 0.33
    """Probability P# of a don't-care symbol in covering."""
    prediction_init: float = 10.0
    """Initial prediction p_I of a new classifier."""
    error_init: NonNegative = 0.0
    """Initial prediction error ε_I."""
    fitness_init: Positive = 0.01
    """Initial fitness F_I."""
    ga_subsumption: bool = True
    """Whether the GA's offspring are subsumed by their parents."""
    action_set_subsumption: bool = False
    """Whether the action set is subsumed by its most general accurate classifier."""


XCS_KEYS = tuple(key for key in XcsParameters.model_fields if key != "scale")


def xcs_keywords(config: XcsParameters, **changes: object) -> dict[str, object]:
    """The config's XCS parameters as keyword arguments of ``XCS`` (with ``changes``)."""
    return {**{key: getattr(config, key) for key in XCS_KEYS}, **changes}


class Table71(XcsParameters):
    """Thesis Table 7.1's XCS, chosen for NAO experiments of a few dozen trials and used by
    the chapter-3 tasks too (§3.5.7); what the table does not give is the learner's own."""

    N: Annotated[int, Field(ge=1)] = 100
    gamma: Probability = 0.7
    beta_p: Rate | None = 0.2
    beta_e: Rate | None = 0.2
    beta_f: Rate | None = 0.2
    p_hash: Probability = 0.6
    theta_ga: Count = 5
