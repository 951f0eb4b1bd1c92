"""``ch4-exploration``: active vs random exploration of the held lid and handle (thesis Figs
4.4–4.9): averaged absolute TD error per step, the step at which (4.10) holds, and the learned
1-D forward models as slices of the surface over state × action."""

from __future__ import annotations

import numpy as np

from robot.reproduce._ch4 import (
    CONFIGURATIONS,
    METHODS,
    N_RANDOM,
    SETUPS,
    TOLERANCE,
    rounded,
)
from robot.reproduce._ch4_variants import converged_counts, summarize_variants, variant_listing
from robot.reproduce.framework import (
    Comparison,
    Figure,
    Panel,
    Progress,
    Reproduction,
    Series,
    mean_and_std,
)

PERCEPTION = "truth"
SURFACE_STATES = (0.0, 0.03, 0.06, 0.09, 0.12)
"""The state slices of the forward-model surfaces (s_o, share of the image): the fully opened
can fills about 0.12–0.13 of the ``close`` camera's image (the thesis's NAO camera saw up to
0.135, and Figs 4.4–4.5 span 0–0.2)."""
SURFACE_ACTIONS = tuple(np.round(np.linspace(-0.01, 0.01, 11), 4))
"""Δx (m) along each slice (Figs 4.4 and 4.5: the action axis from −0.01 to 0.01 m)."""


def run_seed(seed: int, scale: float, progress: Progress, perception: str = PERCEPTION) -> dict:
    """Every configuration and method for one seed, each run to the whole budget N_s.

    Running past the first step at which (4.10) holds changes nothing before it (the run is
    the same), and gives whole curves to plot; ``converged_at`` is that step, as Algorithm 3
    would have stopped there.
    """
    from robot.reproduce._ch4 import explore

    result: dict = {"perception": perception, "configurations": {}}
    jobs = [(name, method) for name in CONFIGURATIONS for method in METHODS]
    for done, (name, method) in enumerate(jobs):
        setup = SETUPS[name]
        explorer, contact = explore(setup, method, seed, scale, perception, stop=False)
        history = explorer.history_
        run = {
            "converged_at": history.converged_at,
            "steps": history.steps,
            "averaged": rounded(history.averaged, 8),
            "td_errors": rounded(history.td_errors, 8),
            "states": rounded(history.states[:, 0]),
            "effects": rounded(history.effects[:, 0]),
            "actions": rounded(history.actions),
        }
        if setup.dims == 1:
            actions = np.array(SURFACE_ACTIONS)[:, None]
            run["surface"] = [rounded(explorer.forward_model_.predict_effects([s], actions))
                              for s in SURFACE_STATES]
        contact.world.close()
        result["configurations"].setdefault(name, {})[method] = run
        progress((done + 1) / len(jobs))
    return result


def summarize(seeds: list[dict]) -> dict:
    """Per configuration and method: seeds that met (4.10), and the median step over those
    (the thesis's test, as Algorithm 3 ran it); under ``variants``, the same two numbers for
    each labelled VARIANT criterion (not the thesis's), evaluated on the same recorded TD
    errors: ``variants.<criterion>.<configuration>.<method>``."""
    summary: dict = {}
    for name in CONFIGURATIONS:
        summary[name] = {}
        for method in METHODS:
            steps = [seed["configurations"][name][method]["converged_at"] for seed in seeds]
            summary[name][method] = converged_counts(steps)
    summary["variants"] = summarize_variants(seeds)
    return summary


def compare(summary: dict, seeds: list[dict]) -> list[Comparison]:
    """Share of seeds converged (thesis: active converged, random did not, in one run each),
    the steps to convergence (the thesis gives curves, not numbers), how far each method opened
    the can (§4.6.2: active exploration covers the state space more thoroughly), and how
    often the TD error was positive (when CACLA moves its actor, 4.8)."""
    rows = []
    for name in CONFIGURATIONS:
        figure = {"lid-1d": "4.6", "lid-3d": "4.7", "handle-1d": "4.8", "handle-3d": "4.9"}[name]
        for method in METHODS:
            runs = [seed["configurations"][name][method] for seed in seeds]
            share = [1.0 if run["converged_at"] is not None else 0.0 for run in runs]
            mean, spread = mean_and_std(share)
            rows.append(Comparison(f"{name} {method}: share of seeds converged (4.10)", mean,
                                   spread, 1.0 if method == "active" else 0.0,
                                   f"Fig. {figure} (one run)"))
            steps = [run["converged_at"] for run in runs]
            mean, spread = mean_and_std(steps)
            rows.append(Comparison(f"{name} {method}: step of convergence", mean, spread))
            mean, spread = mean_and_std([max(run["states"]) for run in runs])
            rows.append(Comparison(f"{name} {method}: largest s_o reached in N_s steps", mean,
                                   spread))
            mean, spread = mean_and_std([float(np.mean(np.array(run["td_errors"]) > 0))
                                         for run in runs])
            rows.append(Comparison(f"{name} {method}: share of steps with δ > 0", mean,
                                   spread))
            mean, spread = mean_and_std([_stable_share(run) for run in runs])
            rows.append(Comparison(f"{name} {method}: share of steps k > N with |e_o| < "
                                   f"{STABLE}", mean, spread))
            mean, spread = mean_and_std([_firing_share(run) for run in runs])
            rows.append(Comparison(f"{name} {method}: share of steps k > N at which (4.10) "
                                   "holds", mean, spread))
            mean, spread = mean_and_std([float(np.std(np.abs(run["td_errors"][N_RANDOM:])))
                                         for run in runs])
            rows.append(Comparison(f"{name} {method}: spread (std) of |δ| over steps k > N",
                                   mean, spread))
            mean, spread = mean_and_std([run["averaged"][-1] for run in runs])
            rows.append(Comparison(f"{name} {method}: averaged |δ| (4.11) at step N_s", mean,
                                   spread))
            if SETUPS[name].dims == 1:
                mean, spread = mean_and_std([float(_opens_as_thesis(run, OPENING[name]))
                                             for run in runs])
                rows.append(Comparison(f"{name} {method}: F predicts opening for Δx of Fig. "
                                       f"{SURFACE_FIGURE[name]}'s sign at every s_o slice",
                                       mean, spread, 1.0, f"Fig. {SURFACE_FIGURE[name]}"))
    return rows


OPENING = {"lid-1d": 1.0, "handle-1d": -1.0}
"""The sign of Δx that opens the part (Figs 4.4–4.5: extend to open the lid, pull the handle)."""
SURFACE_FIGURE = {"lid-1d": "4.4", "handle-1d": "4.5"}


def _opens_as_thesis(run: dict, opening: float) -> bool:
    """Whether the learned 1-D F predicts a larger effect at Δx = +0.01 m than at −0.01 m
    times ``opening`` on every slice: the slope of Figs 4.4–4.5's surfaces."""
    return all((row[-1] - row[0]) * opening > 0 for row in run["surface"])


STABLE = 0.01
"""An effect this small counts as none (τ of eq. 4.15, thesis: 0.01): the state is stable."""


def _stable_share(run: dict) -> float:
    """Of the steps after the first N random ones, the share whose effect was below STABLE."""
    return float(np.mean(np.abs(np.array(run["effects"][N_RANDOM:])) < STABLE))


def _firing_share(run: dict) -> float:
    """Of the steps after the first N, the share at which (4.10) held: its chance per step.

    (4.10) is tested from δ̄_(N+1) on; holding at a share p of the steps, it first holds
    after about 1/p of them whatever came before, when the TD errors are as good as random.
    """
    averaged = np.array([np.nan if v is None else v for v in run["averaged"]], dtype=float)
    changes = np.abs(np.diff(averaged[N_RANDOM - 1:]))
    return float(np.mean(changes < TOLERANCE)) if len(changes) else float("nan")


def _padded(values: list, length: int) -> list[float]:
    """A curve as floats, NaN for missing values and past its end."""
    floats = [np.nan if v is None else float(v) for v in values]
    return floats + [np.nan] * (length - len(floats))


def figures(seeds: list[dict]) -> list[Figure]:
    """Figs 4.6–4.9 (TD-error curves, active vs random) and 4.4–4.5 (1-D surfaces)."""
    out = []
    for name in CONFIGURATIONS:
        length = max(len(seed["configurations"][name][m]["averaged"])
                     for seed in seeds for m in METHODS)
        x = list(range(N_RANDOM, length + 1))  # δ̄_k exists from k = N on (4.11)
        series = [Series(method, x, [
            _padded(seed["configurations"][name][method]["averaged"], length)[N_RANDOM - 1:]
            for seed in seeds]) for method in METHODS]
        out.append(Figure(f"td-{name}", f"{name}: averaged absolute TD error (4.11)",
                          [Panel("step k", "mean |δ| over the last 20 steps", series)]))
    for name in ("lid-1d", "handle-1d"):
        panels = []
        for method in METHODS:
            series = [Series(f"s_o = {state:g}", [100 * a for a in SURFACE_ACTIONS],
                             [seed["configurations"][name][method]["surface"][i]
                              for seed in seeds])
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
Networks: 10 tanh units, weights U[−0.3, 0.3], α = ζ = β = 0.3, σ = 0.2 per unit action
dimension, γ = 0.9; N = 20, ε = 1e−4; the first 20 actions random in both methods (the same
ones for the same seed); N_s = 100 (1-D) and 300 (3-D). Every run goes on to N_s so the curves
are whole; "step of convergence" is the first step at which (4.10) held — where Algorithm 3
stops — and is missing (not averaged) for runs where it never held. Surfaces (Figs 4.4–4.5)
are slices of the learned F at s_o = {", ".join(f"{s:g}" for s in SURFACE_STATES)}.

Reading (4.10). With (4.11), δ̄_(k+1) − δ̄_k = (|δ_(k+1)| − |δ_(k−19)|) / 20, so (4.10) asks
only that two TD errors 20 steps apart agree within 20 ε = 0.002. "share of steps k > N at
which (4.10) holds" is that test's chance per step: a method whose share is p meets (4.10)
after about 1/p steps once the critic's initial transient has flattened, whatever it explored.
"share of steps with |e_o| < 0.01" shows where the part was: stable at an end, or moving.
See docs/results/ch4.md.
"""


TRUTH = ("here from ground truth (the projected gap, which agrees with the rendered frame "
         "within 0.002 + 5 %)")
REPRODUCTION = Reproduction(
    name="ch4-exploration",
    description="Active vs random exploration of the held lid and handle (thesis Figs 4.4-4.9)",
    run_seed=run_seed,
    summarize=summarize,
    compare=compare,
    figures=figures,
    notes=notes(TRUTH),
    listings=variant_listing,
    default_seeds=10,
)
