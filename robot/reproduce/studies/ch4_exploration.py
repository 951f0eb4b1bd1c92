"""``ch4-exploration``: active vs random exploration of the held lid and handle (thesis Figs
4.4–4.9): averaged absolute TD error per step, the step at which (4.10) holds, and the learned
1-D forward models as slices of the surface over state × action."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import product

import numpy as np

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Progress,
    Series,
    Study,
    in_turn,
)
from robot.reproduce.studies.common.ch4 import (
    CH4_DEVIATIONS,
    CONFIGURATIONS,
    METHODS,
    SETUPS,
    Exploration,
    ExplorationRun,
    ScaledExplorationConfig,
    explore,
    rounded,
)
from robot.reproduce.studies.common.ch4_variants import variant_listing

SURFACE_STATES = (0.0, 0.03, 0.06, 0.09, 0.12)
"""The state slices of the forward-model surfaces (s_o, share of the image): the fully opened
can fills about 0.12–0.13 of the ``close`` camera's image (the thesis's NAO camera saw up to
0.135, and Figs 4.4–4.5 span 0–0.2)."""
SURFACE_ACTIONS = tuple(np.round(np.linspace(-0.01, 0.01, 11), 4))
"""Δx (m) along each slice (Figs 4.4 and 4.5: the action axis from −0.01 to 0.01 m)."""
FIGURE = {"lid-1d": "4.6", "lid-3d": "4.7", "handle-1d": "4.8", "handle-3d": "4.9"}
OPENING = {"lid-1d": 1.0, "handle-1d": -1.0}
"""The sign of Δx that opens the part (Figs 4.4–4.5: extend to open the lid, pull the handle)."""
SURFACE_FIGURE = {"lid-1d": "4.4", "handle-1d": "4.5"}
STABLE = 0.01
"""An effect this small counts as none (τ of eq. 4.15, thesis: 0.01): the state is stable."""


def run(config: ScaledExplorationConfig, seed: int, progress: Progress) -> Exploration:
    """Every configuration and method for one seed, each run to the whole budget N_s.

    Running past the first step at which (4.10) holds changes nothing before it (the run is
    the same), and gives whole curves to plot; ``converged_at`` is that step, as Algorithm 3
    would have stopped there.
    """
    runs: dict[str, dict[str, ExplorationRun]] = {name: {} for name in CONFIGURATIONS}
    factor = config.state_scale
    for name, method in in_turn(product(CONFIGURATIONS, METHODS), progress):
        setup = SETUPS[name]
        explorer, contact = explore(setup, method, seed, config, stop=False,
                                    state_scale=factor)
        history = explorer.history_
        surface = None
        if setup.dims == 1:
            actions = np.array(SURFACE_ACTIONS)[:, None]
            surface = [rounded(explorer.forward_model_.predict_effects([s * factor], actions)
                               / factor) for s in SURFACE_STATES]
        contact.world.close()
        runs[name][method] = ExplorationRun(
            converged_at=history.converged_at, steps=history.steps,
            averaged=rounded(history.averaged, 8), td_errors=rounded(history.td_errors, 8),
            states=rounded(history.states[:, 0] / factor),
            effects=rounded(history.effects[:, 0] / factor),
            actions=rounded(history.actions), surface=surface)
    return Exploration(perception=config.perception, configurations=runs)


def opens_as_thesis(run: ExplorationRun, opening: float) -> bool:
    """Whether the learned 1-D F predicts a larger effect at Δx = +0.01 m than at −0.01 m
    times ``opening`` on every slice: the slope of Figs 4.4–4.5's surfaces."""
    return all((row[-1] - row[0]) * opening > 0 for row in run.surface or ())


def stable_share(run: ExplorationRun, n_random: int) -> float:
    """Of the steps after the first N random ones, the share whose effect was below STABLE."""
    return float(np.mean(np.abs(np.array(run.effects[n_random:], dtype=float)) < STABLE))


def firing_share(run: ExplorationRun, config: ScaledExplorationConfig) -> float | None:
    """Of the steps after the first N, the share at which (4.10) held: its chance per step.

    (4.10) is tested from δ̄_(N+1) on; holding at a share p of the steps, it first holds
    after about 1/p of them whatever came before, when the TD errors are as good as random.
    """
    averaged = np.array([np.nan if v is None else v for v in run.averaged], dtype=float)
    changes = np.abs(np.diff(averaged[config.window - 1:]))
    return float(np.mean(changes < config.tolerance)) if len(changes) else None


def metrics(config: ScaledExplorationConfig) -> list[Metric[Exploration]]:
    """Per configuration and method: converged or not (thesis: active converged, random did
    not, in one run each), the step of convergence (the thesis gives curves, not numbers), how
    far each method opened the can (§4.6.2), how often δ was positive (when CACLA moves its
    actor, 4.8), how often the part stood still, how often (4.10) held, the spread and the
    level of |δ|, and whether the 1-D F opens the part as Figs 4.4–4.5 do."""
    rows: list[Metric[Exploration]] = []
    n = config.n_random
    for name, method in product(CONFIGURATIONS, METHODS):
        def get(seed: Exploration, name: str = name, method: str = method) -> ExplorationRun:
            return seed.of(name, method)

        key, label = f"{name}.{method}", f"{name} {method}"
        rows += [
            Metric(f"{key}.converged", f"{label}: seeds converged (4.10)",
                   lambda s, get=get: float(get(s).converged_at is not None),
                   1.0 if method == "active" else 0.0, f"Fig. {FIGURE[name]} (one run)"),
            Metric(f"{key}.converged_at", f"{label}: step of convergence",
                   lambda s, get=get: get(s).converged_at),
            Metric(f"{key}.largest_state", f"{label}: largest s_o reached in N_s steps",
                   lambda s, get=get: max(v for v in get(s).states if v is not None)),
            Metric(f"{key}.positive_td", f"{label}: share of steps with δ > 0",
                   lambda s, get=get: float(np.mean(np.array(get(s).td_errors, float) > 0))),
            Metric(f"{key}.stable_share", f"{label}: share of steps k > N with |e_o| < "
                   f"{STABLE}", lambda s, get=get: stable_share(get(s), n)),
            Metric(f"{key}.firing_share", f"{label}: share of steps k > N at which (4.10) "
                   "holds", lambda s, get=get: firing_share(get(s), config)),
            Metric(f"{key}.td_spread", f"{label}: spread (std) of |δ| over steps k > N",
                   lambda s, get=get: float(np.std(np.abs(np.array(get(s).td_errors[n:],
                                                                   float))))),
            Metric(f"{key}.averaged_at_end", f"{label}: averaged |δ| (4.11) at step N_s",
                   lambda s, get=get: get(s).averaged[-1]),
        ]
        if SETUPS[name].dims == 1:
            rows.append(Metric(
                f"{key}.opens_as_thesis", f"{label}: F predicts opening for Δx of Fig. "
                f"{SURFACE_FIGURE[name]}'s sign at every s_o slice",
                lambda s, get=get, name=name: float(opens_as_thesis(get(s), OPENING[name])),
                1.0, f"Fig. {SURFACE_FIGURE[name]}"))
    return rows


def claims(config: ScaledExplorationConfig) -> list[Claim]:
    out = []
    for name in CONFIGURATIONS:
        figure = f"Fig. {FIGURE[name]}"
        out += [
            Claim(f"{name}: active exploration meets (4.10) within N_s more often than random, "
                  f"which does not ({figure})", f"{name}.active.converged",
                  f"{name}.random.converged"),
            Claim(f"{name}: active exploration's averaged |δ| ends lower than random's "
                  f"({figure}, §4.6.2)", f"{name}.active.averaged_at_end",
                  f"{name}.random.averaged_at_end", "less"),
            Claim(f"{name}: active exploration opens the part further (§4.6.2: it covers the "
                  "state space more thoroughly)", f"{name}.active.largest_state",
                  f"{name}.random.largest_state"),
        ]
    return out


def _padded(values: list, length: int) -> list[float]:
    """A curve as floats, NaN for missing values and past its end."""
    floats = [np.nan if v is None else float(v) for v in values]
    return floats + [np.nan] * (length - len(floats))


def figures(config: ScaledExplorationConfig, seeds: Sequence[Exploration]) -> list[Figure]:
    """Figs 4.6–4.9 (TD-error curves, active vs random) and 4.4–4.5 (1-D surfaces)."""
    out = []
    n = config.window
    for name in CONFIGURATIONS:
        length = max(len(seed.of(name, m).averaged) for seed in seeds for m in METHODS)
        x = list(range(n, length + 1))  # δ̄_k exists from k = N on (4.11)
        series = [Series(method, x, [_padded(seed.of(name, method).averaged, length)[n - 1:]
                                     for seed in seeds]) for method in METHODS]
        out.append(Figure(f"td-{name}", f"{name}: averaged absolute TD error (4.11)",
                          [Panel("step k", f"mean |δ| over the last {n} steps", series)]))
    for name in ("lid-1d", "handle-1d"):
        panels = []
        for method in METHODS:
            series = [Series(f"s_o = {state:g}", [100 * a for a in SURFACE_ACTIONS],
                             [seed.of(name, method).surface[i] for seed in seeds])
                      for i, state in enumerate(SURFACE_STATES)]
            panels.append(Panel(f"{method}: action Δx (cm)", "predicted effect e_o", series))
        out.append(Figure(f"model-{name}", f"{name}: learned forward model F(s_o, Δx)",
                          panels))
    return out


def notes(measured: str) -> str:
    """The setup and the reading of (4.10), with how s_o was ``measured``."""
    return f"""\
Setup (thesis §4.6.1, NAO's geometry). The push-lid can is o1 (the hand presses on the lid's
face and slides over it), the pull-handle can is o5 (the hand grips the handle's bar); moving
back closes what moving forward opened. Each step moves the hand by a = (Δx[, Δy, Δz]), every
component in [−0.01, 0.01] m, with a position-controlled arm that follows its targets; the
arm's reach ends a few centimetres from where it took hold (x: 6 cm back, 2.5 cm forward;
y, z: ±3 cm), so six or so steps one way open the part fully (arm fully stretched or
contracted) and the other way close it (the part's own joint limit), and then the state stays
put. s_o is the dark opening's bounding box as a share of the `close` camera's image
(eq. 4.19), {measured}: 0 closed, about 0.12–0.13 fully open (thesis: up to 0.114–0.135);
e_o = s'_o − s_o (4.20).
Networks, rates, N, ε and N_s are the parameters below (§4.6.1's: 10 tanh units, weights
U[−0.3, 0.3], α = ζ = β = 0.3, σ = 0.2 per unit action dimension, γ = 0.9; N = 20,
ε = 1e−4; N_s = 100 for 1-D and 300 for 3-D); the first N actions are random in both methods
(the same ones for the same seed). Every run goes on to N_s so the curves are whole; "step of
convergence" is the first step at which (4.10) held — where Algorithm 3 stops — and is
missing (not averaged) for runs where it never held. Surfaces (Figs 4.4–4.5) are slices of
the learned F at s_o = {", ".join(f"{s:g}" for s in SURFACE_STATES)}.

Reading (4.10). With (4.11), δ̄_(k+1) − δ̄_k = (|δ_(k+1)| − |δ_(k−19)|) / 20, so (4.10) asks
only that two TD errors 20 steps apart agree within 20 ε = 0.002. "share of steps k > N at
which (4.10) holds" is that test's chance per step: a method whose share is p meets (4.10)
after about 1/p steps once the critic's initial transient has flattened, whatever it explored.
"share of steps with |e_o| < 0.01" shows where the part was: stable at an end, or moving.
See docs/results/ch4.md.
"""


TRUTH = ("here from ground truth (the projected gap, which agrees with the rendered frame "
         "within 0.002 + 5 %)")
STUDY = Study(
    name="ch4-exploration",
    description="Active vs random exploration of the held lid and handle (thesis Figs 4.4-4.9)",
    config=ScaledExplorationConfig, result=Exploration, run=run, metrics=metrics, claims=claims,
    figures=figures, notes=notes(TRUTH), listings=variant_listing,
    quick={"scale": 0.05}, default_seeds=10, deviations=CH4_DEVIATIONS,
    headline=tuple(f"{configuration}.{method}.{metric}"
                   for configuration in CONFIGURATIONS
                   for metric in ("converged", "converged_at") for method in METHODS),
)
