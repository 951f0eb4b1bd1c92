"""The toy study test_workbench.py runs the workbench on, in a module of its own: the worker
processes of a run with two jobs import the module that defines the study, and this one
imports only the framework (the test module's, pytest and matplotlib among them, were two
thirds of each worker's start-up: 0.75 s CPU, now 0.25 s)."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from robot.reproduce.framework import (
    Claim,
    Figure,
    Metric,
    Panel,
    Reference,
    ScaledConfig,
    SeedResult,
    Series,
    Study,
)


class ToyConfig(ScaledConfig):
    offset: float = 0.0
    """Added to every value."""
    choice: Literal["plain", "doubled"] = "plain"
    """Whether the value is doubled."""
    fail_seed: int | None = None
    """A seed that raises (None: none)."""
    interrupt_seed: int | None = None
    """A seed that raises KeyboardInterrupt, as Ctrl-C would."""
    cans: tuple[str, ...] = ("o1",)
    """A tuple-typed parameter."""
    steps: Annotated[int, Field(ge=1)] = 3
    """A parameter with a limit."""
    log: str = ""
    """A file each run appends its seed to (empty: none)."""


class ToyResult(SeedResult):
    value: float
    curve: list[float]
    reached: int | None


def toy_run(config: ToyConfig, seed: int, progress) -> ToyResult:
    if config.log:
        with open(config.log, "a", encoding="utf-8") as handle:
            handle.write(f"{seed}\n")
    if seed == config.fail_seed:
        raise ArithmeticError("no luck")
    if seed == config.interrupt_seed:
        raise KeyboardInterrupt
    for step in range(config.steps):
        progress(step / config.steps)
    value = (seed * seed * config.scale + config.offset) * (2 if config.choice == "doubled"
                                                            else 1)
    return ToyResult(value=value, curve=[seed, seed + 1.0], reached=seed if seed % 2 else None)


def toy_metrics(config: ToyConfig) -> list[Metric[ToyResult]]:
    return [Metric("value", "the value", lambda s: s.value, 2.0, "by hand"),
            Metric("reached", "where odd seeds got", lambda s: s.reached),
            Metric("shifted", "the value plus one", lambda s: s.value + 1.0)]


def toy_claims(config: ToyConfig) -> list[Claim]:
    return [Claim("values grow beyond zero", "value", 0.0, "greater"),
            Claim("adding one adds", "shifted", "value", "greater")]


def toy_figures(config: ToyConfig, seeds) -> list[Figure]:
    return [Figure("curve", "A curve", [Panel("x", "y", [
        Series("seed curve", [0.0, 1.0], [seed.curve for seed in seeds])],
        [Reference(1.0, "one"), Reference(0.5, "half", vertical=True)])])]


TOY = Study(name="toy-run", description="a toy", config=ToyConfig, result=ToyResult,
            run=toy_run, metrics=toy_metrics, claims=toy_claims, figures=toy_figures,
            quick={"scale": 0.5}, headline=("value",))
