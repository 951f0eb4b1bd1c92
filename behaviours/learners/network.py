"""A one-hidden-layer tanh network trained online, one sample at a time (thesis eq. 4.4).

Chapter 4 uses three such networks (forward model, actor, critic): linear inputs, one hidden
layer of tanh units, a linear output, weights drawn uniformly in [−scale, scale], and every
update of the form w ← w + rate · err · ∇_w out (eq. 4.4, 4.8 and 4.9 in network form).

Why not scikit-learn's ``MLPRegressor``: its ``partial_fit`` with ``solver="sgd"``,
``momentum=0``, ``alpha=0``, ``batch_size=1`` and a constant learning rate takes exactly this
step (its output delta is ŷ − y per output, not averaged over outputs), and the tests use it
as the reference for that. But it (1) draws its own (Glorot) initial weights, so the thesis's
uniform [−0.3, 0.3] can only be put in after a throw-away first update or through a private
method, and (2) spends ~350 µs per ``partial_fit`` and ~110 µs per ``predict`` on validation
and bookkeeping (measured on this machine), so the three networks of one CACLA step would
cost ~1.4 ms against the 1 ms target; the numpy step below costs ~15 µs.
"""

from __future__ import annotations

import numpy as np

__all__ = ["TanhNetwork"]


class TanhNetwork:
    """Weights of an (n_in → n_hidden tanh → n_out linear) network and its online SGD step.

    ``coefs`` and ``intercepts`` follow ``MLPRegressor``'s layout: ``coefs[0]`` is
    (n_in, n_hidden), ``coefs[1]`` is (n_hidden, n_out).
    """

    def __init__(self, coefs: list[np.ndarray], intercepts: list[np.ndarray]) -> None:
        """Wrap given weights (copied, as float arrays)."""
        self.coefs = [np.array(c, dtype=float) for c in coefs]
        self.intercepts = [np.array(b, dtype=float) for b in intercepts]
        (n_in, n_hidden), (n_hidden_out, n_out) = (c.shape for c in self.coefs)
        if n_hidden != n_hidden_out or self.intercepts[0].shape != (n_hidden,) or (
                self.intercepts[1].shape != (n_out,)):
            raise ValueError("network weights have inconsistent shapes")

    @classmethod
    def uniform(
        cls, n_in: int, n_hidden: int, n_out: int, scale: float, rng: np.random.RandomState
    ) -> TanhNetwork:
        """All weights and biases drawn uniformly in [−scale, scale] (thesis §4.6.1)."""
        shapes = [(n_in, n_hidden), (n_hidden, n_out)]
        coefs = [rng.uniform(-scale, scale, size=shape) for shape in shapes]
        intercepts = [rng.uniform(-scale, scale, size=shape[1]) for shape in shapes]
        return cls(coefs, intercepts)

    @property
    def n_inputs(self) -> int:
        """Width of an input row."""
        return int(self.coefs[0].shape[0])

    @property
    def n_outputs(self) -> int:
        """Width of an output row."""
        return int(self.coefs[1].shape[1])

    def predict(self, inputs: np.ndarray) -> np.ndarray:
        """Outputs (n, n_out) for input rows (n, n_in)."""
        hidden = np.tanh(inputs @ self.coefs[0] + self.intercepts[0])
        return hidden @ self.coefs[1] + self.intercepts[1]

    def nudge(self, x: np.ndarray, error: np.ndarray, rate: float) -> None:
        """w ← w + rate · Σ_j error_j ∂out_j/∂w at input row ``x`` (one step of eq. 4.4).

        With error = target − out(x) this is one plain-SGD step on ½‖target − out‖².
        """
        hidden = np.tanh(x @ self.coefs[0] + self.intercepts[0])
        back = (self.coefs[1] @ error) * (1.0 - hidden * hidden)  # before W2 changes
        self.coefs[1] += rate * np.outer(hidden, error)
        self.intercepts[1] += rate * error
        self.coefs[0] += rate * np.outer(x, back)
        self.intercepts[0] += rate * back

    def to_dict(self) -> dict[str, list]:
        """Weights as nested lists (JSON-ready)."""
        return {"coefs": [c.tolist() for c in self.coefs],
                "intercepts": [b.tolist() for b in self.intercepts]}

    @classmethod
    def from_dict(cls, data: dict) -> TanhNetwork:
        """Rebuild from ``to_dict`` output; ValueError/KeyError/TypeError if malformed."""
        coefs = [np.asarray(c, dtype=float) for c in data["coefs"]]
        intercepts = [np.asarray(b, dtype=float) for b in data["intercepts"]]
        if len(coefs) != 2 or len(intercepts) != 2 or any(c.ndim != 2 for c in coefs):
            raise ValueError("a network has two weight matrices and two bias vectors")
        if not all(np.all(np.isfinite(a)) for a in coefs + intercepts):
            raise ValueError("network weights must be finite numbers")
        return cls(coefs, intercepts)
