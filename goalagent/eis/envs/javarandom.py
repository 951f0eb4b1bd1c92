"""Java's ``java.util.Random`` in Python, so a seed gives what the Java environments give.

BW4T places blocks and draws random sequences, and the elevator simulator draws its riders,
with ``java.util.Random(seed)``. Reproducing the documented generator (a 48-bit linear
congruential generator; the algorithms are spelled out in the class's Javadoc) makes the same
seed give the same riders and the same random maps here as there. Python's ``random`` uses a
different generator, hence this small module of our own.
"""

from __future__ import annotations

import math

_MULTIPLIER = 0x5DEECE66D
_ADDEND = 0xB
_MASK = (1 << 48) - 1


def _signed32(value: int) -> int:
    """``value`` as Java's 32-bit two's-complement ``int``."""
    value &= 0xFFFFFFFF
    return value - (1 << 32) if value >= 1 << 31 else value


def _java_string_hash(text: str) -> int:
    """``String.hashCode()``: over UTF-16 code units, in 32-bit arithmetic."""
    value = 0
    for unit in text.encode("utf-16-be").hex(" ", 2).split():
        value = (31 * value + int(unit, 16)) & 0xFFFFFFFF
    return value


def java_hashmap_order(keys: list[str]) -> list[str]:
    """The order a ``java.util.HashMap<String, ...>`` filled with ``keys`` iterates them.

    BW4T keeps the blocks of each room in a HashMap and places random extra blocks by walking
    its keys; following the same order makes a seeded map put the same blocks in the same
    rooms as BW4T does. Buckets in ascending order, insertion order within a bucket.
    """
    size = 16
    while len(keys) > size * 3 // 4:
        size *= 2

    def bucket(key: str) -> int:
        value = _java_string_hash(key)
        return (value ^ (value >> 16)) & (size - 1)

    return [key for _, key in sorted(enumerate(keys), key=lambda pair: (bucket(pair[1]), pair[0]))]


class JavaRandom:
    """``java.util.Random``: ``nextInt``, ``nextInt(bound)``, ``nextDouble``, ``nextGaussian``."""

    def __init__(self, seed: int) -> None:
        self._seed = (seed ^ _MULTIPLIER) & _MASK
        self._next_gaussian: float | None = None

    def _next(self, bits: int) -> int:
        """The next ``bits`` random bits as a signed Java int (``Random.next``)."""
        self._seed = (self._seed * _MULTIPLIER + _ADDEND) & _MASK
        return _signed32(self._seed >> (48 - bits))

    def next_int(self) -> int:
        """A uniformly drawn 32-bit signed integer (``nextInt()``)."""
        return self._next(32)

    def next_int_below(self, bound: int) -> int:
        """A uniform integer in ``[0, bound)`` (``nextInt(bound)``), with Java's rejection rule."""
        if bound <= 0:
            raise ValueError(f"bound must be positive, got {bound}")
        if bound & -bound == bound:  # a power of two
            return (bound * self._next(31)) >> 31
        while True:
            bits = self._next(31)
            value = bits % bound
            if _signed32(bits - value + (bound - 1)) >= 0:
                return value

    def next_double(self) -> float:
        """A uniform float in ``[0, 1)`` (``nextDouble()``)."""
        return ((self._next(26) << 27) + self._next(27)) * (1.0 / (1 << 53))

    def next_gaussian(self) -> float:
        """A standard normal draw by the polar method (``nextGaussian()``)."""
        if self._next_gaussian is not None:
            value, self._next_gaussian = self._next_gaussian, None
            return value
        while True:
            v1 = 2 * self.next_double() - 1
            v2 = 2 * self.next_double() - 1
            s = v1 * v1 + v2 * v2
            if 0 < s < 1:
                break
        multiplier = math.sqrt(-2 * math.log(s) / s)
        self._next_gaussian = v2 * multiplier
        return v1 * multiplier
