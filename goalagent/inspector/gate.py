"""Who may reach the mind inspector and how much they may send.

Every HTTP and WebSocket request must name the inspector's own address in its ``Host``
header (127.0.0.1, localhost, ::1 or the ``--host`` given, at the inspector's port: a page
that rebinds its own DNS name to 127.0.0.1 sends its name), come from the inspector's own
origin when it says where it comes from (``Origin``; a browser always says so on a WebSocket,
so the socket requires it), and carry the run's random token (printed in the URL the run
shows). What a page sends on the socket is bounded: its size, its shape (a flat JSON object
of known fields) and its rate.

Hand-written as one small ASGI wrapper rather than Starlette's middleware: its
TrustedHostMiddleware ignores ports, and nothing there checks an Origin or a token on a
WebSocket.
"""

from __future__ import annotations

import ipaddress
import json
import secrets
import time
from typing import Any
from urllib.parse import parse_qs, urlsplit

from starlette.responses import PlainTextResponse
from starlette.types import ASGIApp, Receive, Scope, Send
from starlette.websockets import WebSocketClose

MAX_MESSAGE = 64 * 1024  # characters of one message a page may send (beyond: an error)
MAX_FRAME = 1024 * 1024  # bytes of one WebSocket frame read at all (beyond: closed, 1009)
MAX_SOCKETS = 16  # browsers connected at once
BURST, RATE = 100, 30.0  # messages a socket (and all together) may send at once, then a second
_LOCAL = ("127.0.0.1", "localhost", "::1")
_WILDCARD = ("0.0.0.0", "::", "")
# The fields a message may have, and their types (op is one of OPS).
_FIELDS: dict[str, type] = {"op": str, "text": str, "agent": str, "index": int}
OPS = ("step", "run", "pause", "break", "unbreak", "query", "history")


def new_token() -> str:
    """A fresh random token for one run (192 bits, URL-safe)."""
    return secrets.token_urlsafe(24)


def _split_host(netloc: str, default_port: int) -> tuple[str, int] | None:
    """``host:port`` (``[v6]:port``; no port: the default) as a lower-case name and a port."""
    try:
        parts = urlsplit(f"//{netloc}")
        port = parts.port
    except ValueError:
        return None
    if parts.hostname is None or parts.username is not None or parts.path:
        return None
    return parts.hostname.lower(), default_port if port is None else port


class Gate:
    """The ASGI wrapper in front of the inspector's app: refuses (HTTP 403, or a refused
    WebSocket handshake) every request that is not from the inspector's own page."""

    def __init__(self, app: ASGIApp, host: str, token: str) -> None:
        self.app = app
        self.host = host.lower().strip("[]")
        self.token = token
        self.port: int | None = None  # known once the server listens

    def _own_host(self, name: str, port: int) -> bool:
        if port != self.port:
            return False
        if name in _LOCAL or name == self.host:
            return True
        if self.host in _WILDCARD:  # listening everywhere: any address, never a name
            try:
                ipaddress.ip_address(name)
            except ValueError:
                return False
            return True
        return False

    def refusal(self, scope: Scope) -> str | None:
        """Why a request is refused, or None."""
        headers = {key.decode("latin-1").lower(): value.decode("latin-1")
                   for key, value in scope.get("headers", [])}
        host = _split_host(headers.get("host", ""), 80)
        if host is None or not self._own_host(*host):
            return "this is not the inspector's address (Host)"
        origin = headers.get("origin")
        if origin is None and scope["type"] == "websocket":
            return "a WebSocket must say where it comes from (Origin)"
        if origin is not None:
            parts = urlsplit(origin)
            own = (parts.scheme == "http" and parts.path == ""
                   and (where := _split_host(parts.netloc, 80)) is not None
                   and self._own_host(*where))
            if not own:
                return "only the inspector's own page may talk to it (Origin)"
        given = parse_qs(scope.get("query_string", b"").decode("latin-1")).get("token", [""])
        if len(given) != 1 or not secrets.compare_digest(given[0], self.token):
            return "the run's token is missing or wrong (open the URL the run printed)"
        return None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket"):
            why = self.refusal(scope)
            if why is not None:
                if scope["type"] == "http":
                    await PlainTextResponse(f"forbidden: {why}\n", 403)(scope, receive, send)
                else:
                    await WebSocketClose(code=1008, reason=why)(scope, receive, send)
                return
        await self.app(scope, receive, send)


class Budget:
    """How many messages may be sent now (a token bucket: ``BURST`` at once, refilled at
    ``RATE`` a second); over budget, it says so at most once a second."""

    def __init__(self) -> None:
        self._left = float(BURST)
        self._at = time.monotonic()
        self._warned_at = float("-inf")

    def take(self) -> bool:
        """One message's worth; False when over budget."""
        now = time.monotonic()
        self._left = min(float(BURST), self._left + (now - self._at) * RATE)
        self._at = now
        if self._left >= 1:
            self._left -= 1
            return True
        return False

    def warn(self) -> bool:
        """True when no warning was given in the last second (answer that one only)."""
        now = time.monotonic()
        if now - self._warned_at < 1:
            return False
        self._warned_at = now
        return True


def parse_message(frame: dict[str, Any]) -> dict[str, Any] | str:
    """A received WebSocket frame as a message (a dict of known fields), or why not."""
    text = frame.get("text")
    if not isinstance(text, str):
        return "messages are JSON text, not binary"
    if len(text) > MAX_MESSAGE:
        return f"a message of {len(text):,} characters: at most {MAX_MESSAGE:,}"
    try:
        message = json.loads(text)
    except (ValueError, RecursionError) as err:  # a 5,000-digit number, 100,000 brackets
        return f"not a JSON message: {str(err)[:200]}"
    if not isinstance(message, dict):
        return "a message is a JSON object"
    for key, value in message.items():
        kind = _FIELDS.get(key)
        if kind is None or type(value) is not kind:
            return f"a message has the fields op, text, agent, index; not {key[:40]!r} " \
                   f"of that type"
    if message.get("op") not in OPS:
        return f"unknown op {str(message.get('op'))[:40]!r}: one of {', '.join(OPS)}"
    return message
